// OpenCV's HOG + linear SVM people detector (Dalal & Triggs), with every detectMultiScale parameter
// exposed, a person-height range that sets how far the image is upscaled and how many pyramid levels
// are searched, optional motion regions of interest, and boxes shrunk from the detector window to the
// body (the PETS/MOT convention).
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>

#include <opencv2/objdetect.hpp>

#include "bodyrec/detection/motion_regions.h"
#include "bodyrec/detection/people_detector.h"
#include "bodyrec/detection/person_height_model.h"

namespace bodyrec {

// OpenCV's people SVMs: the 64x128 INRIA one (kDefault) or the 48x96 Daimler one.
enum class HogModel { kDefault, kDaimler };
const char* to_string(HogModel model);                        // "default", "daimler"
std::optional<HogModel> parse_hog_model(const std::string& text);  // the inverse

struct HogOptions {
  HogModel model = HogModel::kDefault;
  double hit_threshold = -0.2;    // SVM score a window must exceed
  int win_stride = 12;            // window step in pixels of the (resized) image
  int padding = 16;               // detectMultiScale padding
  double scale = 1.05;            // pyramid step
  int group_threshold = 2;        // detectMultiScale grouping (0 = raw windows, then only our NMS)
  double resize = 1.0;            // image scale factor before detection (>1 finds smaller people)
  int levels = 64;                // pyramid levels searched (1 = only the resized size)
  cv::Rect roi;                   // region of interest in frame pixels; empty = whole frame
  bool motion_roi = false;        // search only around moving regions (see MotionRegions)
  MotionRegionOptions motion;
  double nms_iou = 0.4;           // our NMS after grouping
  // detect_near: the search window around an expected body box grows by this fraction of its size on
  // each side, and heights within local_height_margin of the expected height are searched.
  double local_region_margin = 0.3;
  double local_height_margin = 0.15;
  // Scene-adaptive scales (with motion regions, for a fixed camera): after `adapt_after` confident
  // detections, a PersonHeightModel limits each region's search to the heights people can have there
  // (within adapt_margin of the fitted line, inside [min_height, max_height]). 0 = off.
  int adapt_after = 0;
  double adapt_margin = 0.2;
  double adapt_min_score = 0.5;   // detections at least this confident teach the model
  double min_height = 0, max_height = 0;  // set by set_height_range; 0 = not set (no adaptation)
  // Where the body sits in the detector window, as fractions of the window (measured on PETS boxes).
  double body_width = 0.50, body_height = 0.75, body_center_x = 0.52, body_center_y = 0.48;

  // Sets resize and levels so that people from min_height to max_height pixels tall (in the frame) are
  // searched: the smallest fills the window at the first level, the tallest at the last.
  void set_height_range(double min_height, double max_height);
  void check() const;  // throws UsageError naming the bad field
};

// Presets: kThesis (the thesis's Ch4 call: hit -0.2, stride 12, padding 16, scale 1.05, group 2, original
// size, whole frame), kDefault (tuned on vtest.avi for AP50 per millisecond: motion regions, people 60-140 px)
// and kOpenCv (OpenCV's peopledetect sample: hit 0, stride 8, no padding, scale 1.05, group 2, its
// window-to-body shrink).
enum class HogPreset { kDefault, kThesis, kOpenCv };
const char* to_string(HogPreset preset);                         // "default", "thesis", "opencv"
std::optional<HogPreset> parse_hog_preset(const std::string& text);  // the inverse
HogOptions hog_preset(HogPreset preset);

class HogPeopleDetector : public PeopleDetector {
 public:
  explicit HogPeopleDetector(const HogOptions& options);
  std::vector<Detection> detect(const cv::Mat& frame) override;
  // Searches a window around each expected box, over heights within local_height_margin of its height.
  // Motion regions and the height model are neither used nor updated.
  std::vector<Detection> detect_near(const cv::Mat& frame, const std::vector<Box>& expected) override;
  std::string describe() const override;

  // Detector windows (frame pixels) and scores before shrinking to the body and before our NMS, with the
  // configured resize factor and pyramid levels.
  std::vector<Detection> detect_windows(const cv::Mat& frame, const cv::Rect& region);

  // The body box inside a detector window.
  Box body_box(const Box& window) const;

 private:
  struct Search {
    double resize;
    int levels;
    int padding;
  };
  // How to search `region`: the configured scales, or the adaptive ones once the height model is ready.
  Search plan(const cv::Rect& region) const;
  std::vector<Detection> search(const cv::Mat& frame, const cv::Rect& region, const Search& how) const;
  // Body boxes of the windows found in `regions` (clipped), after our NMS.
  std::vector<Detection> search_regions(const cv::Mat& frame, const std::vector<std::pair<cv::Rect, Search>>& plan) const;
  const cv::HOGDescriptor& hog_for(int levels) const;

  HogOptions options_;
  mutable std::map<int, cv::HOGDescriptor> hogs_;  // a cache by pyramid levels (nlevels is a descriptor member)
  std::optional<MotionRegions> motion_;
  std::optional<PersonHeightModel> heights_;
};

}  // namespace bodyrec
