// A plain camera's calibration as the colour re-identification pipeline uses it: image points on the floor
// to ground metres (walking directions in metres, views from them), and statures from a person's feet and
// head when the calibration knows the whole camera. Read from `--homography` (image -> ground, no
// statures) or `--calibration` (a Tsai calibration, PETS 2009 layout: statures too) by io/ground_plane.h;
// wrapped here because that header's GroundPlane and rgbd's (the floor of an RGB-D sensor) share a name
// and cannot meet in one file.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include <opencv2/core.hpp>

namespace bodyrec {

enum class GroundFile { kHomography, kCalibration };

class ColourGround {
 public:
  virtual ~ColourGround() = default;
  // Ground position (metres) of an image point on the floor.
  virtual cv::Point2d to_ground(const cv::Point2d& pixel) const = 0;
  // The stature (metres) of someone standing at image point `foot` whose head top is on the row of
  // `head`; nullopt without a camera model (a homography) or when the points cannot be a person.
  virtual std::optional<double> stature_m(const cv::Point2d& foot, const cv::Point2d& head) const = 0;
  virtual std::string describe() const = 0;
};

// Reads the file. InputError naming the file and the field at fault, as io/ground_plane.h says.
std::unique_ptr<ColourGround> read_colour_ground(const std::string& path, GroundFile kind);
// The same from a homography matrix image -> ground metres (tests, tools).
std::unique_ptr<ColourGround> colour_ground_from_homography(const cv::Matx33d& image_to_ground, const std::string& name);

}  // namespace bodyrec
