// People on a static camera from background subtraction: a background model (OpenCV MOG2, shadows not
// counted as foreground) on a downscaled copy of each frame, its foreground cleaned (opened, then closed
// with a tall kernel so that a body's parts join), and every component tall enough to be a person is one
// detection. A component much wider than a person (people side by side, or passing each other) is split
// at the columns where its foreground is thinnest, into parts about as wide as a person of its height.
//
// Cheap (a few ms per frame), and it finds people whatever their pose or how they are dressed, but only
// while they move now and then: someone who stands still for longer than the model's history fades into
// the background, and a moving camera sees everything as foreground. The foreground mask (ForegroundModel)
// also cuts each person out of their box for re-identification (reid/colour_scan.h).
//
//   ForegroundPeopleDetector people({});
//   for (Frame f; source.read(f);) {
//     const std::vector<Detection> found = people.detect(f.image);
//     const cv::Mat body = people.model().mask_in(box);  // 255 = foreground, box size
//   }
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/video/background_segm.hpp>

#include "bodyrec/detection/people_detector.h"

namespace bodyrec {

struct ForegroundOptions {
  double work_width = 480;        // the model runs on a copy this wide (pixels; narrower frames as they are)
  int history = 500;              // MOG2 history (frames): someone still for this long becomes background
  double var_threshold = 16;      // MOG2 variance threshold
  int warmup_frames = 10;         // frames the model learns before it reports anyone
  double min_height = 0.08;       // components shorter than this share of the frame height are not people
  double min_fill = 0.2;          // ... nor those whose foreground fills less of their box
  double max_aspect = 0.9;        // a component wider than this x its height is split ...
  double person_aspect = 0.4;     // ... into parts about this x its height wide; one narrower is one person
  void check() const;             // UsageError naming the field
};

// The background model and its cleaned foreground.
class ForegroundModel {
 public:
  explicit ForegroundModel(const ForegroundOptions& options = {});
  // Learns one frame (BGR, any size; the same size every call) and computes its foreground.
  void update(const cv::Mat& frame);
  // The cleaned foreground at work size (CV_8U, 255 = foreground); empty before the first update.
  const cv::Mat& mask() const { return mask_; }
  // Work size / frame size.
  double scale() const { return scale_; }
  // The foreground inside `box` (frame pixels, clipped to the frame) at the box's size: CV_8U, 255 =
  // foreground. Empty when the box is outside the frame or before the first update.
  cv::Mat mask_in(const cv::Rect& box) const;
  int frames() const { return frames_; }
  const ForegroundOptions& options() const { return options_; }

 private:
  ForegroundOptions options_;
  cv::Ptr<cv::BackgroundSubtractorMOG2> model_;
  cv::Mat small_, raw_, mask_;
  cv::Size frame_size_;
  double scale_ = 1;
  int frames_ = 0;
};

// Splits the foreground component `component` (CV_8U 0/255, work size) whose bounding box is `box` into
// people, each part the bounding box of its pixels: wider than max_aspect x its height, into parts about
// person_aspect x its height wide cut at the thinnest columns near the even cuts; narrower than
// person_aspect x its height, itself; in between, at the gaps between heads (runs of foreground at least a
// tenth of its height wide in a band of rows in its top 30 %), itself when there is one head.
std::vector<cv::Rect> split_component(const cv::Mat& component, const cv::Rect& box, const ForegroundOptions& options);

class ForegroundPeopleDetector : public PeopleDetector {
 public:
  explicit ForegroundPeopleDetector(const ForegroundOptions& options = {});
  // Updates the model with the frame, then one detection per person-sized component (score 0.5 + 0.5 x the
  // share of the box that is foreground). Nobody during warm-up.
  std::vector<Detection> detect(const cv::Mat& frame) override;
  std::string describe() const override;
  const ForegroundModel& model() const { return model_; }

 private:
  ForegroundModel model_;
};

}  // namespace bodyrec
