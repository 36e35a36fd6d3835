#include "bodyrec/detection/dpm_people_detector.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <opencv2/core/persistence.hpp>
#include <opencv2/dpm.hpp>
#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/core/model_files.h"

namespace bodyrec {
namespace {

const char* const kModelName = "inriaperson.xml";
const char* const kDebianModel = "/usr/share/doc/opencv-doc/examples/dpm/data/inriaperson.xml";

double median(std::vector<double> v) {
  const size_t n = v.size();
  std::sort(v.begin(), v.end());
  return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

// OpenCV's loader accepts any readable XML (a missing field reads as zero or empty) and the detector then
// fails or crashes on the first image: check the fields it reads and that their sizes agree.
void check_dpm_model(const std::string& path) {
  cv::FileStorage fs;
  try {
    if (!fs.open(path, cv::FileStorage::READ)) throw InputError("cannot read DPM model " + path);
  } catch (const cv::Exception& e) {
    throw InputError(path + ": not a DPM cascade model (" + e.err + ")");
  }
  auto fail = [&](const std::string& why) { throw InputError(path + ": not a DPM cascade model (" + why + ")"); };
  auto positive = [&](const char* field) {
    const cv::FileNode n = fs[field];
    if (!n.isInt() || static_cast<int>(n) < 1) fail(std::string(field) + " missing or not a positive integer");
    return static_cast<int>(n);
  };
  const int components = positive("NumComponents");
  for (const char* field : {"SBin", "Interval", "MaxSizeX", "MaxSizeY", "NumFeatures", "PCADim"}) positive(field);
  if (!fs["ScoreThreshold"].isReal() && !fs["ScoreThreshold"].isInt()) fail("ScoreThreshold missing");
  if (fs["PCAcoeff"].empty()) fail("PCAcoeff missing");
  auto sized = [&](const char* field, size_t expected) {
    const cv::FileNode n = fs[field];
    if (n.size() != expected)
      fail(std::string(field) + " has " + std::to_string(n.size()) + " entries, expected " + std::to_string(expected));
  };
  for (const char* field : {"Bias", "RootFilters", "RootPCAFilters", "NumParts", "PrunThreshold", "PartOrder",
                            "LocationWeight"})
    sized(field, static_cast<size_t>(components));
  size_t parts = 0;
  for (const cv::FileNode& n : fs["NumParts"]) {  // written as reals ("8.000000")
    const double count = n.isInt() || n.isReal() ? static_cast<double>(n) : -1.0;
    if (!(count >= 0 && count <= 1000 && count == std::floor(count))) fail("NumParts holds a value that is not a count");
    parts += static_cast<size_t>(count);
  }
  for (const char* field : {"PartFilters", "PartPCAFilters", "Anchor", "Deformation"}) sized(field, parts);
}

}  // namespace

struct DpmPeopleDetector::Model {
  cv::Ptr<cv::dpm::DPMDetector> detector;
};

Box BoxCorrection::apply(const Box& b) const {
  const double cx = b.x + b.width / 2 + center_x * b.width, cy = b.y + b.height / 2 + center_y * b.height;
  const double w = b.width * width, h = b.height * height;
  return Box(cx - w / 2, cy - h / 2, w, h);
}

BoxCorrection fit_box_correction(const std::vector<std::vector<Detection>>& detections,
                                 const std::vector<std::vector<Box>>& truth, double min_iou) {
  std::vector<double> dx, dy, sw, sh;
  for (size_t i = 0; i < truth.size() && i < detections.size(); ++i)
    for (const Box& t : truth[i]) {
      const Detection* best = nullptr;
      double best_iou = min_iou;
      for (const Detection& d : detections[i]) {
        const double o = iou(d.box, t);
        if (o >= best_iou && d.box.width > 0 && d.box.height > 0) {
          best_iou = o;
          best = &d;
        }
      }
      if (!best) continue;
      const Box& d = best->box;
      dx.push_back((t.x + t.width / 2 - d.x - d.width / 2) / d.width);
      dy.push_back((t.y + t.height / 2 - d.y - d.height / 2) / d.height);
      sw.push_back(t.width / d.width);
      sh.push_back(t.height / d.height);
    }
  if (dx.empty()) return {};
  return {median(dx), median(dy), median(sw), median(sh)};
}

std::vector<Detection> correct_detections(const std::vector<Detection>& raw, const BoxCorrection& correction,
                                          const cv::Size& frame, double nms_iou) {
  std::vector<Detection> out;
  for (const Detection& d : raw) {
    const Box b = clip_box(correction.apply(d.box), frame);
    if (b.area() > 0) out.push_back({b, d.score});
  }
  return finalize_detections(non_max_suppression(std::move(out), nms_iou));
}

void DpmOptions::check() const {
  if (model_path.empty()) throw UsageError("a DPM detector needs a model file");
  if (!(correction.width > 0 && correction.height > 0)) throw UsageError("DPM box correction: sizes must be > 0");
  if (!(nms_iou > 0 && nms_iou <= 1)) throw UsageError("--nms-iou must be in (0, 1]");
}

std::string dpm_person_model_path() {
  if (auto found = find_model_file(kModelName)) return *found;
  std::error_code ec;
  if (std::filesystem::is_regular_file(kDebianModel, ec)) return kDebianModel;
  std::string searched;
  for (const std::string& dir : model_directories()) searched += dir + ", ";
  throw InputError(std::string("DPM person model ") + kModelName + " not found (searched: " + searched + kDebianModel +
                   "); install Debian's opencv-doc (scripts/install-deps) or put the file in $BODYREC_MODELS");
}

DpmOptions dpm_photo_preset() {
  DpmOptions o;
  o.model_path = dpm_person_model_path();
  // fit_box_correction on the Penn-Fudan training split (128 images, 312 people; eval/photo_preset_data_test.cc
  // chose it by cross-validation there): the INRIA root window is as tall as the body but narrower than its
  // arms and stride.
  o.correction = {0.014, 0.019, 1.087, 1.004};
  return o;
}

DpmPeopleDetector::DpmPeopleDetector(const DpmOptions& options) : options_(options), model_(std::make_unique<Model>()) {
  options_.check();
  std::ifstream in(options_.model_path);
  if (!in) throw InputError("cannot read DPM model " + options_.model_path);
  check_dpm_model(options_.model_path);
  try {
    model_->detector = cv::dpm::DPMDetector::create({options_.model_path});
  } catch (const cv::Exception& e) {
    throw InputError(options_.model_path + ": not a DPM cascade model (" + e.err + ")");
  }
  if (!model_->detector || model_->detector->isEmpty())
    throw InputError(options_.model_path + ": not a DPM cascade model (expected a .xml file)");
}

DpmPeopleDetector::~DpmPeopleDetector() = default;

std::vector<Detection> DpmPeopleDetector::detect_raw(const cv::Mat& frame) {
  cv::Mat image = frame;  // the detector converts its argument to doubles in place: give it its own header
  // OpenCV's DPM fails on images under about 122 px a side (its feature pyramid has no level): pad them at the
  // right and bottom, where no box starts, to kMinSide.
  constexpr int kMinSide = 128;
  if (!frame.empty() && (frame.cols < kMinSide || frame.rows < kMinSide))
    cv::copyMakeBorder(frame, image, 0, std::max(0, kMinSide - frame.rows), 0, std::max(0, kMinSide - frame.cols),
                       cv::BORDER_CONSTANT, cv::Scalar::all(0));
  std::vector<cv::dpm::DPMDetector::ObjectDetection> found;
  model_->detector->detect(image, found);
  std::vector<Detection> out;
  for (const auto& d : found) out.push_back({Box(d.rect), static_cast<double>(d.score)});
  return out;
}

std::vector<Detection> DpmPeopleDetector::detect(const cv::Mat& frame) {
  return correct_detections(detect_raw(frame), options_.correction, frame.size(), options_.nms_iou);
}

std::string DpmPeopleDetector::describe() const {
  std::ostringstream s;
  s << "OpenCV DPM cascade (" << options_.model_path << ", box correction centre " << options_.correction.center_x
    << ", " << options_.correction.center_y << " size x" << options_.correction.width << ", x"
    << options_.correction.height << ")";
  return s.str();
}

}  // namespace bodyrec
