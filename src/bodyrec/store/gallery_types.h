// Plain data kept in the biometric gallery (thesis Ch6, 3D Partial Scans Models): users, their best scan
// per view, and the event history. See gallery.h for the class that stores them.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "bodyrec/core/view.h"

namespace bodyrec {

// Times on the system clock; stored as integer milliseconds since the Unix epoch (UTC). A `time` is the
// source's clock (when it happened in the recording, apps/bodyrec/source_clock.h); `created`, `stored`
// and `logged` are the wall clock when the gallery wrote the row.
using GalleryClock = std::chrono::system_clock;
using GalleryTime = GalleryClock::time_point;
using UserId = int64_t;

// One partial scan as the caller hands it to the gallery.
struct GalleryScan {
  View view = View::F;
  cv::Mat image;     // background-removed person, 8-bit BGR or grey; may be empty (features only)
  cv::Mat mask;      // 8-bit foreground mask (0 / non-zero) of the same size; may be empty
  cv::Mat features;  // the matcher's descriptor(s): any continuous cv::Mat; required, non-empty
  std::string descriptor;      // which matcher made `features`, e.g. "kaze" or "stripes-xqda"
  int descriptor_version = 1;  // bump when the same matcher's features change meaning
  // Higher is better; only compared between scans of one user and view. Callers compute it from how
  // sharp, complete and large the body image is (PartialScan::quality in reid/partial_scan.h).
  double quality = 0;
  GalleryTime time = GalleryClock::now();
};

// What put_scan did with a scan.
enum class PutResult { kInserted, kReplaced, kKept };
const char* put_result_name(PutResult result);

// One scan as loaded for matching: features only, no pixels (the feature cache holds these).
struct GalleryEntry {
  UserId user = 0;
  View view = View::F;
  cv::Mat features;
  std::string descriptor;
  int descriptor_version = 1;
  double quality = 0;
};

// One stored scan with its encoded pixels (show, export).
struct StoredScan {
  UserId user = 0;
  View view = View::F;
  std::vector<unsigned char> image_png;  // empty when stored without images
  std::vector<unsigned char> mask_png;
  cv::Mat features;
  std::string descriptor;
  int descriptor_version = 1;
  double quality = 0;
  GalleryTime time;
  std::optional<GalleryTime> stored;  // when the gallery wrote it; none in galleries before schema 3
};

struct User {
  UserId id = 0;
  std::string label;  // optional name given by an operator; "" when none
  GalleryTime created, first_seen, last_seen;
  std::array<bool, kViewCount> views{};  // which views have a scan (index = View value)
  int scans = 0;
};

enum class EventKind { kEnrolled, kRecognised, kViewAdded, kScanReplaced, kLeft, kForgotten, kPruned };
const char* event_kind_name(EventKind kind);
std::optional<EventKind> parse_event_kind(const std::string& name);

struct Event {
  int64_t id = 0;                // assigned by the gallery
  std::optional<UserId> user;    // none for forgotten/pruned records (they name nobody)
  EventKind kind = EventKind::kRecognised;
  std::optional<double> score;   // match score for recognised
  std::optional<View> view;
  GalleryTime time = GalleryClock::now();
  std::optional<int64_t> track;  // tracking id of the body in the source
  std::string source;            // recording or camera the event came from; "" when unknown
  std::string sensor;            // the sensor that logged it (reid --sensor-id); "" when unknown
  // When the gallery wrote it (set by Gallery::log_event, not by callers); none in galleries before
  // schema 3.
  std::optional<GalleryTime> logged;
};

// A file where a reid run keeps events it has not yet delivered over MQTT (reid --events). The gallery
// lists these so that an erasure can take the erased users' events out of them too.
struct EventSpoolRecord {
  std::string machine;  // the machine the file is on: its /etc/machine-id (host names repeat)
  std::string host;     // that machine's host name, for people
  std::string path;     // absolute on that machine
  std::string sensor;  // the run's --sensor-id
  GalleryTime first_used = GalleryClock::now(), last_used = GalleryClock::now();
};

// What forget/purge/prune erased.
struct EraseReport {
  std::vector<UserId> users;
  int scans = 0, images = 0, masks = 0, events = 0;
  bool checkpointed = true;  // SQLite: false when another process kept old pages in the WAL (see gallery.h);
                             // PostgreSQL: false when the role may not run CHECKPOINT
  bool scrubbed = true;      // the database was rewritten (VACUUM / VACUUM FULL)
  std::string note;          // what the scrubbing could not do, for the operator; "" when all was done
};

}  // namespace bodyrec
