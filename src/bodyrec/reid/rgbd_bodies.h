// Where the bodies of an RGB-D frame are, with a key that stays with each body while it is in view: the
// front end of orientation and re-identification (thesis Ch6), for recordings and live sensors.
//
// Bodies come from (BodySource):
//  - kSkeleton: the sensor's tracked skeletons, keyed by their tracking ids;
//  - kBodyIndex: the sensor's body-index slots, keyed by SlotKeys (rgbd/slot_keys.h: a slot handed to
//    someone else gets a new key);
//  - kDepth: bodyrec's own depth segmentation (rgbd/segment.h); fragments of one person standing within
//    merge_within_m are merged, and the people are followed on the floor (tracking/floor_tracker.h);
//  - kAuto: skeletons when the recording has them, else the body index, else the depth segmentation.
//
//   RgbdBodyFinder finder(meta, options, std::move(segmenter));  // segmenter: needed for kDepth only
//   for (each frame) { const FoundBodies found = finder.find(frame); ... found.bodies[i].ref ... }
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "bodyrec/reid/orientation_estimator.h"
#include "bodyrec/rgbd/recording.h"
#include "bodyrec/rgbd/segment.h"
#include "bodyrec/rgbd/slot_keys.h"
#include "bodyrec/tracking/floor_tracker.h"

namespace bodyrec {

enum class BodySource { kAuto, kSkeleton, kBodyIndex, kDepth };
const char* to_string(BodySource source);                        // "auto", "skeleton", "body-index", "depth"
std::optional<BodySource> parse_body_source(const std::string& text);  // the inverse

struct RgbdBodiesOptions {
  BodySource from = BodySource::kAuto;
  // Ignore the skeletons' joints (orient from the body pixels' depth); with skeletons, their body-index
  // slots still say where the bodies are.
  bool depth_only = false;
  double merge_within_m = 0.3;  // kDepth: segments whose floor positions are this close are one body
  int min_slot_pixels = 200;    // kBodyIndex: smaller slots are ignored (a hand at the border)
};

// Keys of different sources never collide: skeleton tracking ids as they are; body-index slots
// 1000000 + 10 x appearance + slot (SlotKeys); depth segments kFloorKeyBase + floor track id.
constexpr uint64_t kFloorKeyBase = 2000000;

struct FoundBody {
  BodyRef ref;      // key, skeleton (null without joints), labels and label
  int truth = -1;   // index into frame.truth->people when the recording has ground truth, else -1
};

struct FoundBodies {
  cv::Mat labels;                // the label image the refs point into (body index or segmentation)
  std::vector<FoundBody> bodies;
};

// Whether the bodies of a recording with `meta` come from bodyrec's own depth segmentation.
bool uses_own_segmentation(const RecordingMeta& meta, const RgbdBodiesOptions& options);

class RgbdBodyFinder {
 public:
  // InputError when the recording lacks the stream `options.from` needs (naming `name` and the stream);
  // UsageError when kDepth (or kAuto needing it) comes without a segmenter.
  RgbdBodyFinder(const RecordingMeta& meta, const RgbdBodiesOptions& options, std::optional<DepthSegmenter> segmenter,
                 const std::string& name = "recording");

  // The bodies of one frame (frames in time order).
  FoundBodies find(const RgbdFrame& frame);

 private:
  RecordingMeta meta_;
  RgbdBodiesOptions options_;
  bool use_skeletons_ = false, use_index_ = false;
  std::optional<DepthSegmenter> segmenter_;
  SlotKeys slot_keys_;
  FloorTracker floor_tracker_;
};

}  // namespace bodyrec
