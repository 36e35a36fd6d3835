// dlib imglab XML datasets: images with boxes (optionally labelled, ignored) and named landmark parts.
// The format dlib's training tools and the thesis author's files use (see ../shared/datasets/thesis_ch3).
#pragma once

#include <string>
#include <vector>

#include <opencv2/core/types.hpp>

#include "bodyrec/core/geometry.h"

namespace bodyrec {

struct ImglabPart {
  std::string name;  // e.g. "00".."179"; numeric names give the landmark index
  cv::Point2d point;
};

struct ImglabBox {
  Box box;                        // left, top, width, height in pixels
  std::string label;              // e.g. "body_detected"; may be empty
  bool ignore = false;
  std::vector<ImglabPart> parts;  // in file order
};

struct ImglabImage {
  std::string file;  // as written in the XML (absolute, or relative to the XML's folder)
  std::vector<ImglabBox> boxes;
};

struct ImglabDataset {
  std::string name;
  std::string comment;
  std::vector<ImglabImage> images;
};

// Reads an imglab XML file. Throws InputError naming the file, image and field for malformed XML, a
// missing root, an <image> without 'file', a <box> without top/left/width/height, negative sizes, or a
// <part> without name/x/y.
ImglabDataset read_imglab(const std::string& path);
// The same from XML text; `name` names the source in messages.
ImglabDataset parse_imglab(const std::string& text, const std::string& name);

// Writes an imglab XML file (UTF-8). Throws ProcessingError when the file cannot be written.
void write_imglab(const ImglabDataset& dataset, const std::string& path);

// The image path of `image` as a path usable from the current directory: relative paths are taken
// relative to the folder of the XML file `xml_path`, as dlib does.
std::string resolve_image_path(const std::string& xml_path, const std::string& image_file);

// Landmarks of a box ordered by numeric part name (part "0"/"00" first). Throws InputError naming the
// box when a part name is not a number, repeats, or the numbers are not 0..n-1.
std::vector<cv::Point2d> ordered_parts(const ImglabBox& box, const std::string& where);

}  // namespace bodyrec
