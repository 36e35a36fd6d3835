// An imglab XML landmark/box dataset loaded together with its images, for training and evaluation.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "bodyrec/core/geometry.h"
#include "bodyrec/io/imglab_xml.h"

namespace bodyrec {

struct AnnotatedPerson {
  Box box;
  std::vector<cv::Point2d> landmarks;  // ordered by part number; empty when the box has no parts
  bool ignore = false;                 // imglab ignore='1': neither a hit nor a miss for detector training
};

struct AnnotatedImage {
  std::string path;  // resolved image path
  cv::Mat image;     // BGR, 8-bit (empty when images were not loaded)
  std::vector<AnnotatedPerson> people;
};

struct LandmarkDataset {
  std::vector<AnnotatedImage> images;
  int landmarks = 0;  // parts per annotated box (0 when no box has parts)
  int people() const;
};

// Reads `xml_path` (read_imglab) and, when `load_images`, every image it references (relative to the XML's
// folder). Throws InputError naming the XML, image and box for: unreadable XML, a missing or undecodable
// image, part names that are not 0..n-1, or boxes with different numbers of parts.
LandmarkDataset load_landmark_dataset(const std::string& xml_path, bool load_images = true);

// An imglab box with landmark parts named "00", "01", ... (the thesis author's naming).
ImglabBox imglab_landmark_box(const Box& box, const std::vector<cv::Point2d>& points);

// Writes `data` as imglab XML to `xml_path`, image paths made absolute (e.g. the validation part of a
// training set, to score it again with other options). Throws ProcessingError when it cannot be written.
void write_landmark_dataset(const LandmarkDataset& data, const std::string& xml_path, const std::string& name);

}  // namespace bodyrec
