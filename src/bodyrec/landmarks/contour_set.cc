#include "bodyrec/landmarks/contour_set.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/io/imglab_xml.h"
#include "bodyrec/io/pennfudan.h"
#include "bodyrec/landmarks/landmark_dataset.h"

namespace fs = std::filesystem;

namespace bodyrec {
namespace {

void write_image(const cv::Mat& image, const fs::path& path) {
  if (!cv::imwrite(path.string(), image)) throw ProcessingError("cannot write " + path.string());
}

}  // namespace

void ContourSetOptions::check() const {
  if (pennfudan_dir.empty()) throw UsageError("make-contour-set needs --pennfudan DIR");
  if (out_dir.empty()) throw UsageError("make-contour-set needs --out DIR");
  if (!(box_margin >= 0 && box_margin <= 1)) throw UsageError("--box-margin must be in [0, 1]");
  contour.check();
}

int ContourSetReport::skipped_total() const {
  int n = 0;
  for (const auto& [status, count] : skipped) n += count;
  return n;
}

std::vector<Box> read_pennfudan_boxes(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError("cannot read annotation " + path);
  static const std::regex line_re(
      R"(^Bounding box for object (\d+) .*:\s*\(\s*(\d+)\s*,\s*(\d+)\s*\)\s*-\s*\(\s*(\d+)\s*,\s*(\d+)\s*\)\s*$)");
  std::vector<Box> boxes;
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.rfind("Bounding box for object", 0) != 0) continue;
    std::smatch m;
    const std::string where = path + ":" + std::to_string(line_number);
    if (!std::regex_match(line, m, line_re)) throw InputError(where + ": malformed bounding box line");
    const int object = std::stoi(m[1]);
    const double x0 = std::stod(m[2]), y0 = std::stod(m[3]), x1 = std::stod(m[4]), y1 = std::stod(m[5]);
    if (object != static_cast<int>(boxes.size()) + 1)
      throw InputError(where + ": object " + std::to_string(object) + " out of order");
    if (x1 < x0 || y1 < y0) throw InputError(where + ": Xmax/Ymax below Xmin/Ymin");
    boxes.emplace_back(x0 - 1, y0 - 1, x1 - x0 + 1, y1 - y0 + 1);
  }
  return boxes;
}

Box grow_box(const Box& box, double margin, const cv::Size& image_size) {
  const Box grown(box.x - margin * box.width, box.y - margin * box.height, box.width * (1 + 2 * margin),
                  box.height * (1 + 2 * margin));
  return clip_box(grown, image_size);
}

Box mirror_box(const Box& box, int image_width) {
  return Box(image_width - box.x - box.width, box.y, box.width, box.height);
}

ContourSetReport build_pennfudan_contour_set(const ContourSetOptions& options) {
  options.check();
  const fs::path root(options.pennfudan_dir);
  const fs::path images_dir = root / "PNGImages";
  const std::vector<std::string> names = pennfudan_image_names(options.pennfudan_dir);

  const fs::path out(options.out_dir);
  std::error_code ec;
  fs::create_directories(out / "images", ec);
  if (ec) throw ProcessingError("cannot create " + (out / "images").string() + ": " + ec.message());

  ImglabDataset train, test;
  train.name = "Penn-Fudan body contours (train)";
  test.name = "Penn-Fudan body contours (test)";
  const std::string comment = std::to_string(options.contour.landmarks) +
                              " landmarks per person from the instance masks: point 0 = top of the head, "
                              "clockwise, equally spaced by arc length. Boxes without parts are people "
                              "skipped (touching the border or too small) and marked ignore.";
  train.comment = test.comment = comment;
  ContourSetReport report;

  for (size_t i = 0; i < names.size(); ++i) {
    const bool is_test = pennfudan_is_test(i);
    const std::string stem = fs::path(names[i]).stem().string();
    const fs::path image_path = images_dir / names[i];
    const fs::path mask_path = root / "PedMasks" / (stem + "_mask.png");
    const cv::Mat image = cv::imread(image_path.string(), cv::IMREAD_COLOR);
    if (image.empty()) throw InputError("cannot read image " + image_path.string());
    const cv::Mat mask = cv::imread(mask_path.string(), cv::IMREAD_GRAYSCALE);
    if (mask.empty()) throw InputError("cannot read mask " + mask_path.string());
    if (mask.size() != image.size()) throw InputError(mask_path.string() + ": size differs from its image");
    const std::vector<Box> boxes = read_pennfudan_boxes((root / "Annotation" / (stem + ".txt")).string());

    double max_value = 0;
    cv::minMaxLoc(mask, nullptr, &max_value);
    const int people = std::max(static_cast<int>(max_value), static_cast<int>(boxes.size()));
    ImglabImage entry, mirrored;
    entry.file = "images/" + names[i];
    mirrored.file = "images/" + stem + "_flip.png";
    for (int k = 1; k <= people; ++k) {
      const BodyContour contour = contour_from_mask(mask == k, options.contour);
      const Box annotated = k <= static_cast<int>(boxes.size()) ? boxes[static_cast<size_t>(k - 1)] : Box(contour.bounds);
      if (annotated.area() <= 0) continue;  // no mask pixels and no box: nothing there
      const Box box = grow_box(annotated, options.box_margin, image.size());
      if (contour.status != ContourStatus::kOk) {
        ++report.skipped[contour.status];
        ImglabBox ignored;
        ignored.box = box;
        ignored.ignore = true;
        entry.boxes.push_back(ignored);
        ignored.box = mirror_box(box, image.cols);
        mirrored.boxes.push_back(ignored);
        continue;
      }
      entry.boxes.push_back(imglab_landmark_box(box, contour.points));
      mirrored.boxes.push_back(
          imglab_landmark_box(mirror_box(box, image.cols), mirror_contour(contour.points, image.cols)));
      ++(is_test ? report.test_people : report.train_people);
    }
    write_image(image, out / entry.file);
    (is_test ? test : train).images.push_back(entry);
    ++(is_test ? report.test_images : report.train_images);
    if (options.flip && !is_test) {
      cv::Mat flipped;
      cv::flip(image, flipped, 1);
      write_image(flipped, out / mirrored.file);
      for (const auto& b : mirrored.boxes) report.flipped_people += b.ignore ? 0 : 1;
      train.images.push_back(mirrored);
    }
  }
  write_imglab(train, (out / "train.xml").string());
  write_imglab(test, (out / "test.xml").string());
  return report;
}

}  // namespace bodyrec
