// OpenCV's cascade deformable part model detector (Felzenszwalb et al., opencv_contrib `dpm`) with the
// INRIA person model Debian ships in opencv-doc: whole upright people of any size in still photos, from the
// image alone (no motion, no scale range to set). Its boxes are the model's root windows, moved to the body
// by a BoxCorrection measured on the Penn-Fudan training split.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "bodyrec/detection/people_detector.h"

namespace bodyrec {

// Maps a detector box to the body box: the centre moves by (center_x * width, center_y * height) and the
// size is multiplied by (width, height).
struct BoxCorrection {
  double center_x = 0, center_y = 0;
  double width = 1, height = 1;
  Box apply(const Box& box) const;
};

// The correction that maps `detections` onto `truth` (one list of each per image): for every truth box,
// the detection of its image overlapping it most, when that IoU is at least `min_iou`, gives one sample of
// each of the four numbers; the result is their medians. Identity when no truth box is matched.
BoxCorrection fit_box_correction(const std::vector<std::vector<Detection>>& detections,
                                 const std::vector<std::vector<Box>>& truth, double min_iou = 0.3);

// Raw detector boxes -> what PeopleDetector::detect promises: corrected, clipped to `frame`, empty boxes
// dropped, non-maximum suppression at `nms_iou`, rounded for output.
std::vector<Detection> correct_detections(const std::vector<Detection>& raw, const BoxCorrection& correction,
                                          const cv::Size& frame, double nms_iou);

struct DpmOptions {
  std::string model_path;     // a cascade DPM model in opencv_contrib's XML format
  BoxCorrection correction;
  double nms_iou = 0.4;
  void check() const;         // throws UsageError naming the bad field
};

// `inriaperson.xml` in the model directories (core/model_files.h), else Debian's copy in opencv-doc
// (/usr/share/doc/opencv-doc/examples/dpm/data/inriaperson.xml). Throws InputError naming both places when
// neither has it.
std::string dpm_person_model_path();

// The photo preset: the INRIA person model and the correction fit_box_correction gives on the Penn-Fudan
// training split (checked by the data test DpmPhotoPreset).
DpmOptions dpm_photo_preset();

class DpmPeopleDetector : public PeopleDetector {
 public:
  // Throws InputError naming the file when it is missing or not a DPM cascade model.
  explicit DpmPeopleDetector(const DpmOptions& options);
  ~DpmPeopleDetector() override;
  std::vector<Detection> detect(const cv::Mat& frame) override;
  std::string describe() const override;
  // The model's root windows and scores, in frame pixels, before the correction, clipping and our NMS.
  std::vector<Detection> detect_raw(const cv::Mat& frame);

 private:
  struct Model;
  DpmOptions options_;
  std::unique_ptr<Model> model_;
};

}  // namespace bodyrec
