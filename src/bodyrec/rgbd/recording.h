// The bodyrec RGB-D recording: a directory with meta.json and per-frame colour, depth, body index,
// bodies and truth files (docs/recording-format.md is the full specification). RecordingReader yields
// RgbdFrame one by one like io/frame_source; RecordingWriter writes them. Both validate: image sizes
// against the intrinsics, the format version, body slots 0..5, quaternions finite and non-zero, tracked
// joints in front of the camera and near its image (check_joint_positions); every
// error is an InputError (ProcessingError when writing fails) whose one-line message names the file and
// the field.
//
//   RecordingReader rec("rec_synth");
//   for (RgbdFrame f; rec.read(f);) {
//     // f.color BGR (colour intrinsics size), f.depth CV_16U (rec.meta().depth_unit_m per unit),
//     // f.body_index CV_8U or empty, f.bodies, f.truth (synthetic recordings)
//     const cv::Vec3d p = unproject(rec.meta().depth, u, v, f.depth.at<uint16_t>(v, u) * rec.meta().depth_unit_m);
//     const auto in_colour = project(rec.meta().color, rec.meta().depth_to_color.apply(p));
//   }
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>
#include <opencv2/core.hpp>

#include "bodyrec/io/frame_folder.h"  // frame_stem: recordings name their frame files the same way
#include "bodyrec/rgbd/camera.h"
#include "bodyrec/rgbd/skeleton.h"

namespace bodyrec {

constexpr int kRecordingFormatVersion = 1;
constexpr uint8_t kNoBody = 255;  // body index value of pixels that belong to no body

struct BodyJoint {
  cv::Vec3d position{0, 0, 0};            // camera space, metres
  std::optional<Quaternion> orientation;  // nullopt: none (Kinect end joints: head, feet, hand tips, thumbs)
  int tracking_state = 2;                 // 0 not tracked, 1 inferred, 2 tracked
};

struct Body {
  uint64_t tracking_id = 0;  // sensor's id; a person who leaves and comes back gets a new one
  int index = 0;             // slot 0..5: the value of this body's pixels in the body index image
  std::array<BodyJoint, kJointCount> joints;
};

// What the synthetic generator knows about one person in one frame (for evaluating later stages).
struct PersonTruth {
  int identity = 0;           // the same person keeps this across leaving and coming back
  uint64_t tracking_id = 0;   // equals Body::tracking_id of this person's body in the frame
  int body_index = -1;        // slot in the body index image, -1 when not in view
  double yaw_deg = 0;         // facing direction, -180..180; 0 = facing the camera, +90 = facing -X
  double visible_fraction = 0;  // visible depth pixels / pixels of the unoccluded, unclipped body
  int visible_pixels = 0;       // body index pixels of this person
  cv::Rect depth_box;           // visible pixels' bounding box in the depth image (empty when none)
  cv::Vec3d position{0, 0, 0};  // SpineBase, camera space, metres
  double height_m = 0;          // standing height
  std::string top, bottom;      // clothing: "red striped shirt", "blue trousers"
  std::vector<std::string> accessories;  // "hat", "backpack", "shoulder bag"
  cv::Vec3b top_bgr{0, 0, 0}, bottom_bgr{0, 0, 0};
};

struct FrameTruth {
  std::vector<PersonTruth> people;  // every person of the scenario, in or out of view
};

// Everything one frame can hold. Streams a recording does not have stay empty.
struct RgbdFrame {
  int index = 0;
  double time_s = 0;
  cv::Mat color;       // CV_8UC3 BGR, colour intrinsics size
  cv::Mat depth;       // CV_16U, depth units (meta), 0 = invalid, depth intrinsics size
  cv::Mat body_index;  // CV_8U, depth size, 0..5 body slot, 255 none
  std::vector<Body> bodies;
  std::optional<FrameTruth> truth;
};

struct RecordingStreams {
  bool color = false, depth = false, body_index = false, bodies = false, truth = false;
};

struct RecordingMeta {
  int version = kRecordingFormatVersion;
  std::string sensor;           // "Kinect v2", "synthetic", "NTU RGB+D skeleton", ...
  double fps = 30;
  double depth_unit_m = 0.001;  // metres per depth unit
  Intrinsics depth, color;
  Extrinsics depth_to_color;
  std::string color_format = "png";  // "png" or "jpg"
  int frame_count = 0;
  RecordingStreams streams;
};

// JSON conversion with validation. `file` names the source in error messages ("DIR/meta.json").
RecordingMeta meta_from_json(const nlohmann::json& j, const std::string& file);
nlohmann::json to_json(const RecordingMeta& meta);
std::vector<Body> bodies_from_json(const nlohmann::json& j, const std::string& file);
nlohmann::json bodies_to_json(const std::vector<Body>& bodies);
FrameTruth truth_from_json(const nlohmann::json& j, const std::string& file);
nlohmann::json to_json(const FrameTruth& truth);
// Parses a JSON file; InputError naming the file when it is missing or not JSON.
nlohmann::json read_json_file(const std::string& file);
// Parses JSON text; InputError naming `name` when it is not JSON.
nlohmann::json parse_json_text(const std::string& text, const std::string& name);

// Farthest depth of a tracked or inferred joint that check_joint_positions accepts. Body trackers see people
// to about 4.5 m (Kinect v2; its depth reaches 8 m): a joint beyond this is a broken skeleton, not a person.
constexpr double kMaxJointDepthM = 20;

// Checks that every joint the sensor tracked or inferred (tracking_state 1 or 2) is where a depth camera
// could have seen it: in front of the camera (Z > 0), at most kMaxJointDepthM away, and projecting into
// the depth image widened by its own size on every side (a hand inferred just past the edge passes; a
// joint 10^6 m aside does not). Joints not tracked (0) are not checked. Throws InputError
// "FILE: bodies[B].joints[J] (Name).position: tracked joint at (x, y, z) m ..." naming the first bad joint.
void check_joint_positions(const std::vector<Body>& bodies, const Intrinsics& depth, const std::string& file);

// Checks one frame's images against the meta (types, sizes, body index values) and its bodies (slots,
// unique, quaternions, joint positions). Throws InputError naming `where` and the field.
void validate_frame(const RgbdFrame& frame, const RecordingMeta& meta, const std::string& where);

// True when `path` is a recording's directory (it holds meta.json); says nothing of its validity.
bool is_recording_directory(const std::string& path);

class RecordingReader {
 public:
  // Reads and validates DIR/meta.json. Throws InputError when the directory or meta is unusable.
  explicit RecordingReader(const std::string& dir);
  const RecordingMeta& meta() const { return meta_; }
  const std::string& dir() const { return dir_; }
  int frame_count() const { return meta_.frame_count; }
  // Reads the next frame (starting at 0); false after the last. Throws InputError naming the file at
  // fault when a frame's file is missing, unreadable or invalid.
  bool read(RgbdFrame& frame);
  // Random access; REQUIRES 0 <= index < frame_count().
  RgbdFrame read_frame(int index) const;
  void seek(int index) { next_ = index; }

 private:
  std::string dir_;
  RecordingMeta meta_;
  int next_ = 0;
};

class RecordingWriter {
 public:
  // Creates DIR (which must not exist or be empty) and writes meta.json; `meta.frame_count` is ignored.
  // Throws UsageError when DIR is a non-empty directory, ProcessingError when it cannot be created.
  RecordingWriter(const std::string& dir, RecordingMeta meta);
  // Validates and writes one frame as frame number frame_count() (frame.index is ignored), then
  // rewrites meta.json so that a recording stopped at any point is complete up to its last frame.
  void write(const RgbdFrame& frame);
  int frame_count() const { return meta_.frame_count; }
  const RecordingMeta& meta() const { return meta_; }

 private:
  void write_meta() const;
  std::string dir_;
  RecordingMeta meta_;
};

}  // namespace bodyrec
