#include "bodyrec/io/pennfudan.h"

#include <algorithm>
#include <filesystem>
#include <set>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/io/image_file.h"

namespace fs = std::filesystem;

namespace bodyrec {
namespace {

const std::string kMaskSuffix = "_mask.png";

}  // namespace

std::vector<std::string> pennfudan_image_names(const std::string& dir) {
  const fs::path images_dir = fs::path(dir) / "PNGImages";
  std::error_code ec;
  if (!fs::is_directory(images_dir, ec)) throw InputError(images_dir.string() + ": not a folder (expected Penn-Fudan)");
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(images_dir))
    if (entry.path().extension() == ".png") names.push_back(entry.path().filename().string());
  if (names.empty()) throw InputError(images_dir.string() + ": no .png images");
  std::sort(names.begin(), names.end());
  return names;
}

bool pennfudan_is_test(std::size_t index) { return index % 4 == 3; }

bool in_pennfudan_split(std::size_t index, PennFudanSplit split) {
  switch (split) {
    case PennFudanSplit::kTrain: return !pennfudan_is_test(index);
    case PennFudanSplit::kTest: return pennfudan_is_test(index);
    case PennFudanSplit::kAll: return true;
  }
  return false;
}

std::vector<Box> instance_mask_boxes(const cv::Mat& mask, const std::string& name) {
  if (mask.type() != CV_8UC1) throw InputError(name + ": not an 8-bit single-channel instance mask");
  double max_value = 0;
  cv::minMaxLoc(mask, nullptr, &max_value);
  std::vector<Box> boxes;
  for (int k = 1; k <= static_cast<int>(max_value); ++k) {
    const cv::Rect r = cv::boundingRect(mask == k);
    if (r.area() > 0) boxes.emplace_back(r);
  }
  return boxes;
}

std::vector<PennFudanImage> load_pennfudan(const std::string& dir, PennFudanSplit split) {
  const std::vector<std::string> names = pennfudan_image_names(dir);
  const fs::path masks_dir = fs::path(dir) / "PedMasks";
  std::error_code ec;
  if (!fs::is_directory(masks_dir, ec)) throw InputError(masks_dir.string() + ": not a folder (expected Penn-Fudan)");
  // Every mask must belong to an image: a stray mask means the folders are out of step.
  const std::set<std::string> images(names.begin(), names.end());
  std::vector<std::string> masks;
  for (const auto& entry : fs::directory_iterator(masks_dir)) masks.push_back(entry.path().filename().string());
  std::sort(masks.begin(), masks.end());
  for (const std::string& mask : masks) {
    if (mask.size() <= kMaskSuffix.size() || mask.compare(mask.size() - kMaskSuffix.size(), kMaskSuffix.size(), kMaskSuffix) != 0)
      continue;
    if (!images.count(mask.substr(0, mask.size() - kMaskSuffix.size()) + ".png"))
      throw InputError((masks_dir / mask).string() + ": mask without an image in PNGImages/");
  }
  std::vector<PennFudanImage> out;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (!in_pennfudan_split(i, split)) continue;
    PennFudanImage item;
    item.image_path = (fs::path(dir) / "PNGImages" / names[i]).string();
    item.mask_path = (masks_dir / (fs::path(names[i]).stem().string() + kMaskSuffix)).string();
    if (!fs::exists(item.mask_path, ec)) throw InputError(item.mask_path + ": missing (the mask of " + item.image_path + ")");
    const cv::Mat mask = read_image_file(item.mask_path, cv::IMREAD_UNCHANGED);
    item.size = mask.size();
    item.people = instance_mask_boxes(mask, item.mask_path);
    out.push_back(std::move(item));
  }
  return out;
}

}  // namespace bodyrec
