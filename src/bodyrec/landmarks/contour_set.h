// Training data for the shape predictor and the detector from instance masks (Penn-Fudan): one contour
// landmark set per person, written as dlib imglab XML (train.xml, test.xml) with the images beside them.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "bodyrec/core/geometry.h"
#include "bodyrec/landmarks/contour.h"

namespace bodyrec {

struct ContourSetOptions {
  std::string pennfudan_dir;  // holds PNGImages/, PedMasks/, Annotation/
  std::string out_dir;        // receives train.xml, test.xml, images/
  ContourOptions contour;
  double box_margin = 0.0;    // each side grows by this fraction of the box width (left, right) / height (top, bottom)
  bool flip = false;          // add mirrored copies of the training images (the test split stays as it is)
  void check() const;         // throws UsageError
};

struct ContourSetReport {
  int train_images = 0, test_images = 0;        // original images (flipped copies not counted)
  int train_people = 0, test_people = 0;        // people with landmarks (flipped copies not counted)
  int flipped_people = 0;                       // extra mirrored people in train.xml
  std::map<ContourStatus, int> skipped;         // people without landmarks, by reason (written as ignore boxes)
  int skipped_total() const;
};

// The person boxes of a Penn-Fudan annotation file (PASCAL v1.00 text), index k-1 = object k, converted
// from 1-based inclusive corners to 0-based x, y, width, height. Throws InputError naming the file and
// line for an unreadable file or a malformed "Bounding box" line.
std::vector<Box> read_pennfudan_boxes(const std::string& path);

// The box of a person with landmarks: `box` grown by `margin` on every side, clipped to the image.
Box grow_box(const Box& box, double margin, const cv::Size& image_size);

// The box of the left-right mirrored image of width `image_width`.
Box mirror_box(const Box& box, int image_width);

// Builds the set. Split: pennfudan_is_test over the sorted image names (io/pennfudan.h: i % 4 == 3 -> test).
// People whose contour is skipped stay in the XML as ignore boxes without parts, so that detector
// training does not count them as background. Throws InputError naming the file for a missing folder,
// image, mask or annotation; ProcessingError when the outputs cannot be written.
ContourSetReport build_pennfudan_contour_set(const ContourSetOptions& options);

}  // namespace bodyrec
