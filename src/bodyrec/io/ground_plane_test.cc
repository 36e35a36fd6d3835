#include "bodyrec/io/ground_plane.h"

#include <cmath>

#include <gtest/gtest.h>

#include "test_support.h"

namespace bodyrec {
namespace {

using testing::input_error;
using testing::TempDir;
using testing::write_text;

TEST(GroundPlane, HomographyFileWithCommentsAndCommas) {
  TempDir dir;
  write_text(dir / "h.txt", "# image -> ground, metres\n0.01, 0, -1\n0 0.02 -2 # row 2\r\n0\t0\t1\n");
  const auto plane = read_homography((dir / "h.txt").string());
  const cv::Point2d g = plane->to_ground({300, 200});
  EXPECT_NEAR(g.x, 2.0, 1e-12);
  EXPECT_NEAR(g.y, 2.0, 1e-12);
}

TEST(GroundPlane, BrokenHomographyFiles) {
  TempDir dir;
  const std::string f = (dir / "h.txt").string();
  auto error_for = [&](const std::string& text) {
    write_text(dir / "h.txt", text);
    return input_error([&] { read_homography(f); });
  };
  EXPECT_EQ(error_for("1 0 0\n0 1 0\n"), f + ": a homography needs 9 numbers (3x3, row by row), found 6");
  EXPECT_EQ(error_for("1 0 0\n0 x 0\n0 0 1\n"), f + ":2: 'x' is not a finite number");
  EXPECT_EQ(error_for("1 0 0\n0 1 0\n0 0 inf\n"), f + ":3: 'inf' is not a finite number");
  EXPECT_EQ(error_for("1 2 3\n2 4 6\n0 0 1\n"), f + ": the matrix is singular");
  EXPECT_EQ(input_error([&] { read_homography((dir / "none.txt").string()); }),
            (dir / "none.txt").string() + ": cannot open the homography file");
}

const char* kCalibration =
    R"(<Camera name="c"><Geometry width="768" height="576" ncx="795" nfx="752" dx="0.00485" dy="0.00465"
 dpx="0.0051273271277" dpy="0.00465"/><Intrinsic focal="5.5549183034" kappa1="0.0051113043639"
 cx="324.22149053" cy="282.56650051" sx="1.0937855397"/><Extrinsic tx="828.73214225" ty="-3175.4796051"
 tz="35469.298547" rx="2.0405458695" ry="-0.89337703748" rz="-0.43056124791"/></Camera>)";

TEST(GroundPlane, TsaiCalibrationMapsTheImageCentreOntoTheGround) {
  TempDir dir;
  write_text(dir / "cal.xml", kCalibration);
  const auto plane = read_tsai_calibration((dir / "cal.xml").string());
  // Two points 100 px apart in the lower middle of the image are a few metres apart on the ground, and
  // perspective makes the far half of the segment longer on the ground than the near half.
  const cv::Point2d a = plane->to_ground({384, 450}), b = plane->to_ground({384, 350}),
                    m = plane->to_ground({384, 400});
  const double ab = cv::norm(a - b);
  EXPECT_GT(ab, 1.0);
  EXPECT_LT(ab, 10.0);
  EXPECT_GT(cv::norm(a - m) / ab, 0.40);
  EXPECT_LT(cv::norm(a - m) / ab, 0.49);
}

// Tsai's forward model written out here (world mm -> pixel) for the calibration above: a person standing at
// a ground point, seen by this camera, has the stature height_m() measures.
cv::Point2d tsai_pixel(const cv::Vec3d& world_mm) {
  const double rx = 2.0405458695, ry = -0.89337703748, rz = -0.43056124791;
  const double sa = std::sin(rx), ca = std::cos(rx), sb = std::sin(ry), cb = std::cos(ry), sg = std::sin(rz),
               cg = std::cos(rz);
  const cv::Matx33d r(cb * cg, cg * sa * sb - ca * sg, sa * sg + ca * cg * sb, cb * sg, sa * sb * sg + ca * cg,
                      ca * sb * sg - cg * sa, -sb, cb * sa, ca * cb);
  const cv::Vec3d c = r * world_mm + cv::Vec3d(828.73214225, -3175.4796051, 35469.298547);
  const double f = 5.5549183034, kappa1 = 0.0051113043639;
  const double xu = f * c[0] / c[2], yu = f * c[1] / c[2];
  double xd = xu, yd = yu;
  for (int i = 0; i < 50; ++i) {
    const double k = 1 + kappa1 * (xd * xd + yd * yd);
    xd = xu / k;
    yd = yu / k;
  }
  return {1.0937855397 * xd / 0.0051273271277 + 324.22149053, yd / 0.00465 + 282.56650051};
}

TEST(GroundPlane, TsaiCalibrationMeasuresStatures) {
  const auto plane = parse_tsai_calibration(kCalibration, "cal.xml");
  for (const cv::Point2d foot : {cv::Point2d(384, 450), cv::Point2d(200, 300), cv::Point2d(600, 380)}) {
    const cv::Point2d g = plane->to_ground(foot) * 1000.0;
    // The ground point projects back onto the foot pixel: the forward model and to_ground agree.
    const cv::Point2d back = tsai_pixel({g.x, g.y, 0});
    EXPECT_NEAR(back.x, foot.x, 0.05);
    EXPECT_NEAR(back.y, foot.y, 0.05);
    // World Z is up for this camera (its centre is at positive Z).
    for (const double stature : {1.55, 1.75, 1.95}) {
      const cv::Point2d head = tsai_pixel({g.x, g.y, stature * 1000});
      const auto h = plane->height_m(foot, head);
      ASSERT_TRUE(h) << foot;
      EXPECT_NEAR(*h, stature, 0.005) << foot;
    }
    EXPECT_FALSE(plane->height_m(foot, foot + cv::Point2d(0, 5)));  // below the foot: no stature
  }
  // A homography knows the ground only.
  EXPECT_FALSE(homography_ground_plane(cv::Matx33d::eye(), "h")->height_m({10, 100}, {10, 20}));
}

TEST(GroundPlane, BrokenCalibrations) {
  TempDir dir;
  const std::string f = (dir / "cal.xml").string();
  auto error_for = [&](const std::string& text) {
    write_text(dir / "cal.xml", text);
    return input_error([&] { read_tsai_calibration(f); });
  };
  EXPECT_EQ(error_for("<Other/>"), f + ": no <Camera> element (expected a PETS/Tsai calibration)");
  EXPECT_EQ(error_for("<Camera><Geometry dpx='1' dy='1'/><Intrinsic/></Camera>"),
            f + ": <Camera> has no <Extrinsic> element");
  std::string no_focal = kCalibration;
  no_focal.replace(no_focal.find("focal="), 6, "focus=");
  EXPECT_EQ(error_for(no_focal), f + ": <Intrinsic>: missing attribute 'focal'");
  std::string zero_sx = kCalibration;
  zero_sx.replace(zero_sx.find("sx=\"1.0937855397\""), 17, "sx=\"0\"");
  EXPECT_EQ(error_for(zero_sx), f + ": 'sx' must be a positive number");
}

}  // namespace
}  // namespace bodyrec
