#include "bodyrec/detection/fhog_training.h"

#include <algorithm>
#include <cmath>
#include <fstream>

#include <dlib/image_processing.h>
#include <dlib/image_processing/remove_unobtainable_rectangles.h>
#include <dlib/opencv/cv_image.h>
#include <dlib/svm_threaded.h>

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace {

using Scanner = dlib::scan_fhog_pyramid<dlib::pyramid_down<6>>;
using Images = dlib::array<dlib::array2d<dlib::rgb_pixel>>;
using Rects = std::vector<std::vector<dlib::rectangle>>;

dlib::rectangle to_rect(const Box& b) {
  return dlib::rectangle(std::lround(b.x), std::lround(b.y), std::lround(b.x + b.width) - 1,
                         std::lround(b.y + b.height) - 1);
}

// Copies images and boxes into dlib's containers (BGR -> RGB) and upsamples them when asked.
void to_dlib(const std::vector<FhogTrainingImage>& in, bool upsample, Images& images, Rects& boxes, Rects& ignore) {
  images.resize(in.size());
  boxes.assign(in.size(), {});
  ignore.assign(in.size(), {});
  for (size_t i = 0; i < in.size(); ++i) {
    dlib::assign_image(images[i], dlib::cv_image<dlib::bgr_pixel>(in[i].image));
    for (const Box& b : in[i].boxes) boxes[i].push_back(to_rect(b));
    for (const Box& b : in[i].ignore) ignore[i].push_back(to_rect(b));
  }
  if (upsample) dlib::upsample_image_dataset<dlib::pyramid_down<2>>(images, boxes, ignore);
}

}  // namespace

void FhogTrainOptions::check() const {
  const auto fail = [](const char* field, const char* problem) { throw OptionError("FhogTrainOptions", field, problem); };
  if (!(C > 0)) fail("C", "must be > 0");
  if (!(epsilon > 0)) fail("epsilon", "must be > 0");
  if (target_size < 16 || target_size > 1000) fail("target_size", "must be in [16, 1000]");
  if (threads < 1) fail("threads", "must be >= 1");
}

FhogTrainReport train_fhog_detector(const std::vector<FhogTrainingImage>& in, const FhogTrainOptions& options,
                                    const std::string& out_path) {
  options.check();
  Images images;
  Rects boxes, ignore;
  to_dlib(in, options.upsample, images, boxes, ignore);

  std::vector<double> aspects;
  for (const auto& list : boxes)
    for (const auto& r : list) aspects.push_back(static_cast<double>(r.width()) / static_cast<double>(r.height()));
  if (aspects.empty()) throw ProcessingError("no boxes to train the detector on");
  std::nth_element(aspects.begin(), aspects.begin() + static_cast<long>(aspects.size() / 2), aspects.end());
  const double aspect = aspects[aspects.size() / 2];
  FhogTrainReport report;
  report.window = cv::Size(static_cast<int>(std::lround(options.target_size * std::sqrt(aspect))),
                           static_cast<int>(std::lround(options.target_size / std::sqrt(aspect))));

  Scanner scanner;
  scanner.set_detection_window_size(static_cast<unsigned long>(report.window.width),
                                    static_cast<unsigned long>(report.window.height));
  dlib::structural_object_detection_trainer<Scanner> trainer(scanner);
  trainer.set_num_threads(static_cast<unsigned long>(options.threads));
  trainer.set_c(options.C);
  trainer.set_epsilon(options.epsilon);
  if (options.verbose) trainer.be_verbose();

  // Boxes no window position and scale can match (too small, or too far from the window's shape) would
  // make dlib reject the whole labelling: they become "ignore" boxes, counted in the report. After the
  // flip, since a mirrored box need not fall on the window grid.
  if (options.flip) dlib::add_image_left_right_flips(images, boxes, ignore);
  const Rects removed = dlib::remove_unobtainable_rectangles(trainer, images, boxes);
  for (size_t i = 0; i < boxes.size(); ++i) {
    report.unreachable += static_cast<int>(removed[i].size());
    report.boxes += static_cast<int>(boxes[i].size());
    ignore[i].insert(ignore[i].end(), removed[i].begin(), removed[i].end());
  }
  if (report.boxes == 0) throw ProcessingError("no box fits the detection window; change --target-size");

  dlib::object_detector<Scanner> detector;
  try {
    detector = trainer.train(images, boxes, ignore);
  } catch (const dlib::impossible_labeling_error& e) {
    std::string why = e.what();
    std::replace(why.begin(), why.end(), '\n', ' ');
    throw ProcessingError("dlib cannot learn these boxes: " + why);
  }
  std::ofstream out(out_path, std::ios::binary);
  if (!out) throw ProcessingError("cannot write " + out_path);
  dlib::serialize(detector, out);
  out.flush();
  if (!out) throw ProcessingError("cannot write " + out_path);
  return report;
}

DetectionAccuracy test_fhog_detector(const std::string& model_path, const std::vector<FhogTrainingImage>& in,
                                     bool upsample) {
  dlib::object_detector<Scanner> detector;
  std::ifstream file(model_path, std::ios::binary);
  if (!file) throw InputError("cannot read detector model " + model_path);
  try {
    dlib::deserialize(detector, file);
  } catch (const std::exception& e) {
    std::string why = e.what();
    throw InputError(model_path + ": not a dlib fHOG object detector (" + why.substr(0, why.find('\n')) + ")");
  }
  Images images;
  Rects boxes, ignore;
  to_dlib(in, upsample, images, boxes, ignore);
  const dlib::matrix<double, 1, 3> r = dlib::test_object_detection_function(detector, images, boxes, ignore);
  return {r(0), r(1), r(2)};
}

}  // namespace bodyrec
