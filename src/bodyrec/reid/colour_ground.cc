// Only io's GroundPlane here (see colour_ground.h).
#include "bodyrec/reid/colour_ground.h"

#include "bodyrec/io/ground_plane.h"

namespace bodyrec {
namespace {

class IoGround : public ColourGround {
 public:
  explicit IoGround(std::unique_ptr<GroundPlane> plane) : plane_(std::move(plane)) {}
  cv::Point2d to_ground(const cv::Point2d& pixel) const override { return plane_->to_ground(pixel); }
  std::optional<double> stature_m(const cv::Point2d& foot, const cv::Point2d& head) const override {
    return plane_->height_m(foot, head);
  }
  std::string describe() const override { return plane_->describe(); }

 private:
  std::unique_ptr<GroundPlane> plane_;
};

}  // namespace

std::unique_ptr<ColourGround> read_colour_ground(const std::string& path, GroundFile kind) {
  return std::make_unique<IoGround>(kind == GroundFile::kHomography ? read_homography(path)
                                                                    : read_tsai_calibration(path));
}

std::unique_ptr<ColourGround> colour_ground_from_homography(const cv::Matx33d& h, const std::string& name) {
  return std::make_unique<IoGround>(homography_ground_plane(h, name));
}

}  // namespace bodyrec
