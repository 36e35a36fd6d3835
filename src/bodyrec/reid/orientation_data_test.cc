// Orientation on real Kinect v2 skeletons (NTU RGB+D samples, ../shared/datasets/ntu_skeleton).
#include <cmath>
#include <map>

#include <gtest/gtest.h>

#include "bodyrec/reid/orientation_estimator.h"
#include "bodyrec/rgbd/ntu_skeleton.h"
#include "test_support.h"

namespace bodyrec {
namespace {

struct Run {
  int frames = 0;
  std::map<uint64_t, std::vector<ViewEstimate>> per_body;
};

Run orient_file(const std::string& file, ViewMethod method) {
  const NtuSkeleton s = read_ntu_skeleton(file);
  RecordingMeta meta;
  double rms[2];
  fit_ntu_cameras(s, meta, rms);
  OrientationOptions o;
  o.method = method;
  o.use_faces = false;  // no colour in the skeleton files
  OrientationEstimator est(meta, o);
  Run r;
  const auto bodies = ntu_bodies(s, file);
  for (size_t i = 0; i < bodies.size(); ++i) {
    RgbdFrame f;
    f.index = static_cast<int>(i);
    f.time_s = static_cast<double>(i) / 30;
    f.bodies = bodies[i];
    for (const Body& b : f.bodies) r.per_body[b.tracking_id].push_back(est.estimate(f, BodyRef::of(b, cv::Mat())));
    ++r.frames;
  }
  return r;
}

// A056 "giving something to other person", camera 3: the first performer faces the camera (median
// shoulder-and-hip yaw 9 degrees), the second is turned well away from it.
TEST(OrientationNtu, GivingSomethingFirstPersonFacesTheCamera) {
  BODYREC_REQUIRE_DATA(file, "ntu_skeleton/samples/S017C003P020R002A056.skeleton");
  const Run r = orient_file(file.string(), ViewMethod::kRobust);
  EXPECT_EQ(r.frames, 80);
  ASSERT_EQ(r.per_body.size(), 2u);
  const auto& first = r.per_body.begin()->second;  // ids sort as they were assigned here
  EXPECT_EQ(first.size(), 80u);
  int front = 0, jumps = 0;
  for (size_t i = 0; i < first.size(); ++i) {
    ASSERT_TRUE(first[i].view) << first[i].reason;
    front += *first[i].view == View::F;
    if (i > 0) jumps += angle_diff_deg(first[i].yaw_deg, first[i - 1].yaw_deg) > 15;
  }
  EXPECT_GE(front, 60) << "of 80 frames";
  EXPECT_EQ(jumps, 0);  // continuity: no frame-to-frame jump above 15 degrees
}

// Every sample: every body gets a view in every frame from its skeleton, yaws change smoothly, and the
// thesis rule, without a face flag, names the reason when it cannot decide.
TEST(OrientationNtu, AllSamplesContinuousAndThesisSaysWhy) {
  BODYREC_REQUIRE_DATA(dir, "ntu_skeleton/samples");
  int files = 0, bodies = 0, thesis_none = 0, thesis_face_reason = 0, thesis_views = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".skeleton") continue;
    ++files;
    const Run robust = orient_file(entry.path().string(), ViewMethod::kRobust);
    for (const auto& [id, views] : robust.per_body) {
      int big = 0;
      for (size_t i = 0; i < views.size(); ++i) {
        ++bodies;
        ASSERT_TRUE(views[i].view) << entry.path() << " frame " << i << ": " << views[i].reason;
        if (i > 0) big += angle_diff_deg(views[i].yaw_deg, views[i - 1].yaw_deg) > 30;
      }
      EXPECT_LE(big, 2) << entry.path() << " body " << id;
    }
    const Run thesis = orient_file(entry.path().string(), ViewMethod::kThesis);
    for (const auto& [id, views] : thesis.per_body)
      for (const auto& v : views) {
        if (v.view) {
          ++thesis_views;
          continue;
        }
        ++thesis_none;
        EXPECT_FALSE(v.reason.empty());
        thesis_face_reason += v.reason.find("face flag") != std::string::npos;
      }
  }
  EXPECT_EQ(files, 12);
  EXPECT_EQ(bodies, 1567);
  EXPECT_EQ(thesis_views + thesis_none, bodies);
  EXPECT_GT(thesis_face_reason, 0);
}

}  // namespace
}  // namespace bodyrec
