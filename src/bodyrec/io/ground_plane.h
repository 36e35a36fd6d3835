// From image pixels to positions on the ground plane in metres, so that group membership can use real
// distances and speeds. Two sources:
//  - a 3x3 homography image -> ground (metres), as text: nine numbers, row by row, whitespace or commas,
//    '#' comments allowed (`--homography H.txt`);
//  - a Tsai camera calibration in the PETS 2009 XML layout (<Camera><Geometry dpx dy .../><Intrinsic focal
//    kappa1 cx cy sx/><Extrinsic tx ty tz rx ry rz/>, world in millimetres), including its radial lens
//    distortion (`--calibration View_001.xml`).
#pragma once

#include <iosfwd>
#include <memory>
#include <optional>
#include <string>

#include <opencv2/core.hpp>

namespace bodyrec {

class GroundPlane {
 public:
  virtual ~GroundPlane() = default;
  // Ground position (metres) of an image point that lies on the ground (a person's feet).
  virtual cv::Point2d to_ground(const cv::Point2d& pixel) const = 0;
  // The height (metres) of an upright segment standing on the ground at image point `foot` whose top is
  // seen on the image row of `head`: a person's stature from their feet and the top of their head. Needs
  // the whole camera (a Tsai calibration); nullopt for a homography, which maps the ground alone, and when
  // `head` is not above `foot` within 0.3..3 m.
  virtual std::optional<double> height_m(const cv::Point2d& foot, const cv::Point2d& head) const {
    (void)foot;
    (void)head;
    return std::nullopt;
  }
  virtual std::string describe() const = 0;
};

// Throws InputError naming the file and the line/field at fault (not nine numbers, not finite, singular).
std::unique_ptr<GroundPlane> read_homography(const std::string& path);
// The same from a stream; `name` names the source in messages.
std::unique_ptr<GroundPlane> read_homography(std::istream& in, const std::string& name);

// Throws InputError naming the file and the element/attribute at fault.
std::unique_ptr<GroundPlane> read_tsai_calibration(const std::string& path);
// The same from XML text; `name` names the source in messages.
std::unique_ptr<GroundPlane> parse_tsai_calibration(const std::string& text, const std::string& name);

// A ground plane from a homography matrix (tests, tools).
std::unique_ptr<GroundPlane> homography_ground_plane(const cv::Matx33d& image_to_ground, const std::string& name);

}  // namespace bodyrec
