// The Penn-Fudan pedestrian set (PNGImages/NAME.png, PedMasks/NAME_mask.png; Annotation/ is read by
// landmarks/contour_set): its image list, the one train/test split every bodyrec tool uses, and ground-truth
// person boxes from the instance masks.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "bodyrec/core/geometry.h"

namespace bodyrec {

enum class PennFudanSplit { kTrain, kTest, kAll };

// The .png file names in DIR/PNGImages, sorted by name. Throws InputError naming the folder when it is
// missing or holds no .png file.
std::vector<std::string> pennfudan_image_names(const std::string& dir);

// The split over that sorted list: image i (0-based) is a test image when i % 4 == 3 (42 of 170).
bool pennfudan_is_test(std::size_t index);
bool in_pennfudan_split(std::size_t index, PennFudanSplit split);

// The tight box of each person in an instance mask (0 = background, k = person k): one box per value
// 1..max that has pixels, in increasing value order; x, y, width, height in pixels (a one-pixel person is
// 1 x 1). REQUIRES: mask is CV_8UC1 (throws InputError otherwise, naming `name`).
std::vector<Box> instance_mask_boxes(const cv::Mat& mask, const std::string& name = "mask");

struct PennFudanImage {
  std::string image_path;
  std::string mask_path;
  cv::Size size;             // the mask's size; its image must have the same
  std::vector<Box> people;   // instance_mask_boxes of the mask
};

// The images of `split` in sorted order, with their ground truth read from the masks (the images
// themselves are not decoded). Throws InputError naming the file or folder: PNGImages/ or PedMasks/
// missing, no images, an image without its mask, a mask without its image, a mask that cannot be read or
// is not 8-bit single-channel.
std::vector<PennFudanImage> load_pennfudan(const std::string& dir, PennFudanSplit split);

}  // namespace bodyrec
