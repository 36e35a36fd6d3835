#include "bodyrec/io/ground_plane.h"

#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

#include "bodyrec/core/error.h"
#include "bodyrec/core/parse_number.h"
#include "bodyrec/io/xml_document.h"

namespace bodyrec {
namespace {

class HomographyPlane : public GroundPlane {
 public:
  HomographyPlane(const cv::Matx33d& h, std::string name) : h_(h), name_(std::move(name)) {}
  cv::Point2d to_ground(const cv::Point2d& p) const override {
    const cv::Vec3d g = h_ * cv::Vec3d(p.x, p.y, 1.0);
    return {g[0] / g[2], g[1] / g[2]};
  }
  std::string describe() const override { return "homography " + name_; }

 private:
  cv::Matx33d h_;
  std::string name_;
};

// Tsai's model: world (mm) -> camera by R, T; perspective with focal f (mm on the sensor); radial
// distortion Xu = Xd (1 + kappa1 r^2); pixels Xf = sx Xd / dpx + cx, Yf = Yd / dy + cy. The inverse for
// ground points: undistort the pixel, then the ground-to-sensor homography f [r1 r2 T] backwards.
class TsaiPlane : public GroundPlane {
 public:
  // `ground_to_sensor` = f [r1 r2 T] (checked invertible by the caller).
  TsaiPlane(double kappa1, double cx, double cy, double sx, double dpx, double dy, double f, const cv::Matx33d& r,
            const cv::Vec3d& t, const cv::Matx33d& ground_to_sensor, std::string name)
      : kappa1_(kappa1), cx_(cx), cy_(cy), sx_(sx), dpx_(dpx), dy_(dy), f_(f), r_(r), t_(t),
        sensor_to_ground_(ground_to_sensor.inv()), name_(std::move(name)) {
    // World Z is up when the camera centre -R^T T lies on its positive side.
    up_ = (-(r_.t() * t_))[2] >= 0 ? 1.0 : -1.0;
  }
  cv::Point2d to_ground(const cv::Point2d& p) const override {
    const double xd = (p.x - cx_) * dpx_ / sx_, yd = (p.y - cy_) * dy_;
    const double k = 1.0 + kappa1_ * (xd * xd + yd * yd);
    const cv::Vec3d g = sensor_to_ground_ * cv::Vec3d(xd * k, yd * k, 1.0);
    return {g[0] / g[2] / 1000.0, g[1] / g[2] / 1000.0};  // mm -> m
  }
  std::optional<double> height_m(const cv::Point2d& foot, const cv::Point2d& head) const override {
    const cv::Point2d g = to_ground(foot) * 1000.0;  // mm
    const auto row = [&](double h_mm) { return project({g.x, g.y, up_ * h_mm}); };
    // Bisection on the row of the point h above the foot (rows fall as h grows, up to the horizon).
    double lo = 300, hi = 3000;
    const auto r_lo = row(lo), r_hi = row(hi);
    if (!r_lo || !r_hi || !(head.y <= *r_lo && head.y >= *r_hi)) return std::nullopt;
    for (int i = 0; i < 40; ++i) {
      const double mid = (lo + hi) / 2;
      const auto r = row(mid);
      if (!r) return std::nullopt;
      (*r > head.y ? lo : hi) = mid;
    }
    return (lo + hi) / 2 / 1000.0;
  }
  std::string describe() const override { return "Tsai calibration " + name_; }

 private:
  // The image row of a world point (mm), nullopt behind the camera.
  std::optional<double> project(const cv::Vec3d& world) const {
    const cv::Vec3d c = r_ * world + t_;
    if (!(c[2] > 0)) return std::nullopt;
    const double xu = f_ * c[0] / c[2], yu = f_ * c[1] / c[2];
    // Undistorted -> distorted sensor coordinates: Xu = Xd (1 + kappa1 rd^2), solved by fixed-point steps.
    double xd = xu, yd = yu;
    for (int i = 0; i < 20; ++i) {
      const double k = 1.0 + kappa1_ * (xd * xd + yd * yd);
      xd = xu / k;
      yd = yu / k;
    }
    return yd / dy_ + cy_;
  }

  double kappa1_, cx_, cy_, sx_, dpx_, dy_, f_;
  cv::Matx33d r_;
  cv::Vec3d t_;
  double up_ = 1;
  cv::Matx33d sensor_to_ground_;
  std::string name_;
};

void check_invertible(const cv::Matx33d& m, const std::string& what) {
  const double d = cv::determinant(m);
  if (!std::isfinite(d) || std::abs(d) < 1e-12) throw InputError(what + ": the matrix is singular");
}

}  // namespace

std::unique_ptr<GroundPlane> homography_ground_plane(const cv::Matx33d& h, const std::string& name) {
  return std::make_unique<HomographyPlane>(h, name);
}

std::unique_ptr<GroundPlane> read_homography(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the homography file");
  return read_homography(in, path);
}

std::unique_ptr<GroundPlane> read_homography(std::istream& in, const std::string& path) {
  std::vector<double> values;
  std::string line;
  for (int line_no = 1; std::getline(in, line); ++line_no) {
    if (const auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    for (char& c : line)
      if (c == ',' || c == ';' || c == '\r' || c == '\t') c = ' ';
    std::istringstream fields(line);
    std::string field;
    while (fields >> field) {
      const auto v = parse_double(field);
      if (!v || !std::isfinite(*v))
        throw InputError(path + ":" + std::to_string(line_no) + ": '" + field + "' is not a finite number");
      values.push_back(*v);
    }
  }
  if (values.size() != 9)
    throw InputError(path + ": a homography needs 9 numbers (3x3, row by row), found " +
                     std::to_string(values.size()));
  const cv::Matx33d h(values.data());
  check_invertible(h, path);
  return homography_ground_plane(h, path);
}

static std::unique_ptr<GroundPlane> tsai_from_document(const pugi::xml_document& doc, const std::string& path) {
  const pugi::xml_node camera = doc.child("Camera");
  if (!camera) throw InputError(path + ": no <Camera> element (expected a PETS/Tsai calibration)");
  auto node = [&](const char* name) {
    const pugi::xml_node n = camera.child(name);
    if (!n) throw InputError(path + ": <Camera> has no <" + std::string(name) + "> element");
    return n;
  };
  const std::string where = path;
  const auto geometry = node("Geometry"), intrinsic = node("Intrinsic"), extrinsic = node("Extrinsic");
  const double dpx = required_number(geometry, "dpx", where + ": <Geometry>");
  const double dy = required_number(geometry, "dy", where + ": <Geometry>");
  const double f = required_number(intrinsic, "focal", where + ": <Intrinsic>");
  const double kappa1 = required_number(intrinsic, "kappa1", where + ": <Intrinsic>");
  const double cx = required_number(intrinsic, "cx", where + ": <Intrinsic>");
  const double cy = required_number(intrinsic, "cy", where + ": <Intrinsic>");
  const double sx = required_number(intrinsic, "sx", where + ": <Intrinsic>");
  const cv::Vec3d t(required_number(extrinsic, "tx", where + ": <Extrinsic>"),
                    required_number(extrinsic, "ty", where + ": <Extrinsic>"),
                    required_number(extrinsic, "tz", where + ": <Extrinsic>"));
  const double rx = required_number(extrinsic, "rx", where + ": <Extrinsic>");
  const double ry = required_number(extrinsic, "ry", where + ": <Extrinsic>");
  const double rz = required_number(extrinsic, "rz", where + ": <Extrinsic>");
  for (const auto& [name, v] : {std::pair{"dpx", dpx}, {"dy", dy}, {"focal", f}, {"sx", sx}})
    if (!(v > 0) || !std::isfinite(v)) throw InputError(path + ": '" + name + "' must be a positive number");
  // Tsai's rotation from the three angles (as in his reference implementation).
  const double sa = std::sin(rx), ca = std::cos(rx), sb = std::sin(ry), cb = std::cos(ry), sg = std::sin(rz),
               cg = std::cos(rz);
  const cv::Matx33d r(cb * cg, cg * sa * sb - ca * sg, sa * sg + ca * cg * sb,  //
                      cb * sg, sa * sb * sg + ca * cg, ca * sb * sg - cg * sa,  //
                      -sb, cb * sa, ca * cb);
  const cv::Matx33d ground_to_sensor(f * r(0, 0), f * r(0, 1), f * t[0], f * r(1, 0), f * r(1, 1), f * t[1], r(2, 0),
                                     r(2, 1), t[2]);
  check_invertible(ground_to_sensor, path);
  return std::make_unique<TsaiPlane>(kappa1, cx, cy, sx, dpx, dy, f, r, t, ground_to_sensor, path);
}

std::unique_ptr<GroundPlane> read_tsai_calibration(const std::string& path) {
  return tsai_from_document(load_xml_file(path), path);
}

std::unique_ptr<GroundPlane> parse_tsai_calibration(const std::string& text, const std::string& name) {
  return tsai_from_document(parse_xml_text(text, name), name);
}

}  // namespace bodyrec
