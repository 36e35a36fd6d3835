// Depth-only people segmentation (no body index), in the spirit of PCL's ground-based people detection
// (Munaro et al.): foreground = valid depth that is neither background nor ground, where background is an
// optional per-pixel depth model learnt over time (the farthest depth each pixel has seen) and ground is a
// plane fitted by RANSAC to the lower part of the cloud. Foreground pixels are clustered on the organised
// cloud (neighbours join when their depths differ by less than a distance-dependent jump), fragments are
// merged into the person whose ground-plane footprint they touch (left-over fragments that touch each
// other may make a person together), clusters are split at heads (maxima of the height profile across the
// floor, closer than a head distance to no higher bin, and at least 0.15 m prominent unless the top) and
// kept as people when their top lies within the person height range. With a background model, the
// ground band is 3 cm (the floor is background anyway) so that feet stay with their bodies.
//
//   DepthSegmenter seg(meta.depth, meta.depth_unit_m);
//   seg.learn_background(frame.depth);          // optional, over a recording's frames
//   const Segmentation s = seg.segment(frame.depth);
//   // s.labels: CV_8U like a body index (0..5 person, 255 none); s.people[i].box in depth pixels
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <nlohmann/json_fwd.hpp>
#include <opencv2/core.hpp>

#include "bodyrec/rgbd/camera.h"

namespace bodyrec {

struct SegmentOptions {
  double ground_tolerance_m = 0.07;  // points closer than this to the ground plane are ground
  double background_margin_m = 0.06;  // closer than the background by more than this (+ noise) is foreground
  double min_height_m = 1.3;  // a person's top above the ground (PCL's test: 1.3..2.3)
  double max_height_m = 2.3;
  double head_distance_m = 0.25;  // two heads closer than this are one person (PCL: heads_minimum_distance 0.3)
  double min_person_width_m = 0.1;  // narrower clusters are no person
  double max_person_width_m = 1.2;  // wider clusters are split at heads, or dropped
  double merge_distance_m = 0.25;  // a fragment within this of a person's footprint joins it
  double max_range_m = 8.0;        // points farther away are ignored (Kinect-class sensors)
  int max_people = 6;              // Kinect's body limit: the labels use slots 0..5
};

struct SegmentedPerson {
  int label = 0;         // value of this person's pixels in Segmentation::labels
  cv::Rect box;          // bounding box of the pixels, depth image
  int pixels = 0;
  double height_m = 0;   // top above the ground plane
  cv::Vec3d centroid{0, 0, 0};  // camera space, metres
};

struct Segmentation {
  cv::Mat labels;  // CV_8U, depth size; 0..max_people-1 person, 255 (kNoBody) none
  std::vector<SegmentedPerson> people;  // sorted left to right by box x; label = position
  std::optional<cv::Vec4d> ground;      // plane a X + b Y + c Z + d = 0, (a,b,c) unit, pointing up
};

class DepthSegmenter {
 public:
  // REQUIRES valid intrinsics (checked: InputError) and depth_unit_m > 0.
  DepthSegmenter(const Intrinsics& depth_k, double depth_unit_m, SegmentOptions options = {});

  // Adds one frame to the background model (per pixel, the farthest valid depth seen).
  void learn_background(const cv::Mat& depth);
  bool has_background() const { return !background_.empty(); }
  void clear_background() { background_.release(); }

  // Segments one depth frame. Throws InputError when depth is not CV_16U of the intrinsics' size.
  // When no ground plane is found the previous frame's plane is used; without any, heights are measured
  // from the lowest foreground point. The RANSAC sampling restarts from a fixed seed for every frame.
  Segmentation segment(const cv::Mat& depth);

  const SegmentOptions& options() const { return options_; }

 private:
  std::optional<cv::Vec4d> fit_ground(const cv::Mat& depth);
  Intrinsics k_;
  double unit_;
  SegmentOptions options_;
  std::vector<float> ray_x_, ray_y_;
  cv::Mat background_;  // CV_16U, 0 = unknown
  std::optional<cv::Vec4d> last_ground_;
};

class RecordingReader;

// Learns `segmenter`'s background from up to `samples` frames spread evenly over the recording, but only
// when it has at least `min_frames` frames (a single frame would learn the people as background).
// Returns whether a background was learnt. Reads frames by random access; frames the reader cannot read
// (InputError) are left out, so that a broken frame stops the caller's own pass, not this one.
bool learn_recording_background(const RecordingReader& reader, DepthSegmenter& segmenter, int samples = 60,
                                int min_frames = 10);

// Per-frame JSON of a segmentation: {"frame", "people": [{"label", "box": [x,y,w,h], "pixels",
// "height_m", "centroid": [x,y,z]}], "ground": [a,b,c,d] or null}.
nlohmann::json segmentation_to_json(int frame, const Segmentation& s);

// Matches predicted to true person masks by maximal total IoU (exhaustive over at most 6x6).
// `truth` and `predicted` are label images (0..5, 255 none) of the same size. Returns one IoU per true
// person present in `truth` (0 for an unmatched one) and counts predicted people left unmatched.
struct MaskMatch {
  std::vector<double> iou;  // per true person, by ascending label
  int unmatched_predicted = 0;
};
MaskMatch match_masks(const cv::Mat& truth, const cv::Mat& predicted, int min_true_pixels = 0);

}  // namespace bodyrec
