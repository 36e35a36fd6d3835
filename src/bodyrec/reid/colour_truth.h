// Evaluation of colour-only runs on recordings with truth (bodyrec synth): which true person each tracked
// box shows. The recording's body index (which the colour pipeline never sees) is mapped into the colour
// image person by person (PartialScanExtractor::color_mask), and a box shows the person with the most
// visible pixels inside it, when those fill at least min_share of the box.
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "bodyrec/detection/people_detector.h"
#include "bodyrec/rgbd/recording.h"

namespace bodyrec {

struct BoxTruth {
  std::vector<int> person;  // per box: index into frame.truth->people, -1 when none
  int visible = 0;          // people of the truth whose colour mask has at least min_visible_px pixels
};

// REQUIRES frame with truth, depth and body index (else every box gets -1 and visible is 0).
BoxTruth truth_for_boxes(const RecordingMeta& meta, const RgbdFrame& frame, const std::vector<cv::Rect>& boxes,
                         double min_share = 0.2, int min_visible_px = 1500);

// The bodies a perfect detector and tracker would give (diagnosis of the colour path: what its detection and
// tracking lose): each true person's body index mapped into the colour image, with the sensor's tracking
// id (a new one after leaving and coming back, as the RGB-D path sees it). Only people whose colour mask
// has at least min_visible_px pixels.
struct TrueBody {
  int person = -1;         // index into frame.truth->people
  uint64_t track = 0;      // TruthPerson::tracking_id
  cv::Rect box;            // the mask's bounding box in colour pixels
  cv::Mat mask;            // CV_8U, box-sized, 255 = this person
};
std::vector<TrueBody> true_bodies(const RecordingMeta& meta, const RgbdFrame& frame, int min_visible_px = 1500);

// A detector that finds what it is told (diagnosis: true boxes through the real tracker): detect() gives
// the detections of the last set(), each with score 1.
class ListedDetector : public PeopleDetector {
 public:
  void set(const std::vector<cv::Rect>& boxes);
  std::vector<Detection> detect(const cv::Mat& frame) override;
  std::string describe() const override { return "listed boxes"; }

 private:
  std::vector<Detection> next_;
};

}  // namespace bodyrec
