// Views (F, FR, FL, SR, SL, B, BR, BL) of people seen by a plain camera, without a skeleton or depth:
// people walk forwards, so the direction a tracked person walks is the direction their body faces, and a
// face in the head region says the front is turned to the camera (thesis Ch6: faces decide front against
// back).
//
// The walking velocity is a least-squares line through the track's last window_s of positions:
//  - with a ground calibration (colour_ground.h), the feet (bottom centre of the box) on the floor in
//    metres, split into the component towards the camera (the ground direction of "down the image" at the
//    feet) and the one across it;
//  - without, in the image: across from the feet's column, in body heights (x assumed_stature_m), and
//    towards the camera from the growth of the box's height (a body twice as tall is half as far; its
//    distance in body heights is focal / height px, the focal length taken as focal_ratio x the image
//    width). Coarser: box heights jitter with the stride and with what the detector finds.
// yaw = atan2(-across, towards) in bodyrec's convention (orientation.h: 0 faces the camera, +90 faces the
// image's left), the view its 45-degree sector. Front/back evidence per track (capped): the towards
// component while walking, + face_weight when a frontal face is found in the head region, - no_face_weight
// when the head region was looked at and held none (weak: detectors miss). When it clearly contradicts
// the walking yaw's half (someone walking backwards, or sideways with the face seen), the yaw is mirrored
// to the other half on the same side (180 - yaw). A track slower than min_speed keeps its last yaw for
// hold_s (fading confidence); with none, a face gives F. Confidence 0..1: speed x distance to the sector's
// border.
//
//   WalkingViewEstimator views({}, ground);   // ground may be null
//   for (each frame) for (each tracked person) {
//     const ViewEstimate v = views.estimate(track, frame.time_s, box, frame.image);   // v.view, v.yaw_deg
//   }
#pragma once

#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include <opencv2/core.hpp>

#include "bodyrec/reid/colour_ground.h"
#include "bodyrec/reid/face_evidence.h"
#include "bodyrec/reid/orientation.h"

namespace bodyrec {

struct WalkingViewOptions {
  double window_s = 1.0;          // positions over this long give the walking velocity
  int min_samples = 4;            // positions needed in the window
  double min_speed_mps = 0.3;     // slower tracks give no walking direction
  double assumed_stature_m = 1.7; // image mode: metres per body height
  double focal_ratio = 0.6;       // image mode: the camera's focal length over the image width (~80 deg wide)
  double hold_s = 2.0;            // a track that stops keeps its last view this long
  bool use_faces = true;
  std::string face_cascade;       // empty: default_face_cascade()
  int face_every = 3;             // the face detector looks at a track every N-th frame
  double face_weight = 2.0;       // a frontal face found in the head region
  double no_face_weight = 0.15;   // the head region looked at, no face in it
  double motion_weight = 1.0;     // the towards component, per frame, scaled by speed up to 1
  double evidence_cap = 4.0;      // |accumulated front/back evidence| <= this
  double forget_s = 1.0;          // a track unseen this long starts afresh
  void check() const;             // UsageError naming the field
};

class WalkingViewEstimator {
 public:
  // `ground` (may be null) must outlive the estimator. InputError when the face cascade cannot be loaded
  // (only with use_faces).
  explicit WalkingViewEstimator(const WalkingViewOptions& options = {}, const ColourGround* ground = nullptr);
  ~WalkingViewEstimator();

  // The view of track `track` in the frame at `time_s` (increasing per track), its box in frame pixels;
  // `frame` (BGR) for the face detector (may be empty: no faces). `head_x`, when given, the column of the
  // head (e.g. the mask's top rows), else the box's centre.
  ViewEstimate estimate(uint64_t track, double time_s, const cv::Rect& box, const cv::Mat& frame,
                        std::optional<double> head_x = std::nullopt);
  // The face detector's answer for the body just estimated (looked = false when it did not run).
  const FaceResult& last_face() const { return last_face_; }
  // Drops tracks unseen since before `time_s - forget_s`.
  void forget_before(double time_s);

 private:
  struct Track {
    std::deque<std::pair<double, cv::Point2d>> path;  // time, position (ground metres or image feet px)
    std::deque<std::pair<double, double>> heights;    // time, log box height (image mode)
    std::optional<double> yaw;                        // last walking yaw (front/back resolved)
    double yaw_time = -1e9, evidence = 0, last_seen = -1e9, speed = 0;
    int since_face = 1000000;
  };
  // Walking velocity as (across, towards) in m/s; nullopt with too few samples.
  std::optional<cv::Point2d> velocity(const Track& t, const cv::Rect& box, int frame_width) const;

  WalkingViewOptions options_;
  const ColourGround* ground_;
  std::unique_ptr<FaceDetector> faces_;
  std::map<uint64_t, Track> tracks_;
  FaceResult last_face_;
};

}  // namespace bodyrec
