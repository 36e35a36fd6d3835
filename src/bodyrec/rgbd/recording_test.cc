// The recording format: round trips, and one clear InputError per kind of broken input.
#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "bodyrec/rgbd/recording.h"
#include "test_support.h"

namespace bodyrec {
namespace {

using bodyrec::testing::contains;
using bodyrec::testing::input_error;
using bodyrec::testing::TempDir;
using bodyrec::testing::write_text;
using nlohmann::json;

RecordingMeta small_meta() {
  RecordingMeta m;
  m.sensor = "test";
  m.depth = {8, 6, 5, 5, 3.5, 2.5};
  m.color = {16, 12, 10, 10, 7.5, 5.5};
  m.streams = {true, true, true, true, true};
  return m;
}

Body sample_body(int index) {
  Body b;
  b.tracking_id = 72057594037934994ULL + static_cast<uint64_t>(index);  // > 2^53: must survive JSON
  b.index = index;
  for (int j = 0; j < kJointCount; ++j) {
    b.joints[static_cast<size_t>(j)].position = {0.1 * j, -0.05 * j, 2.5};
    b.joints[static_cast<size_t>(j)].orientation = Quaternion::about_y(0.1 * j);
  }
  b.joints[idx(Joint::kHead)].orientation.reset();
  b.joints[idx(Joint::kHandTipLeft)].tracking_state = 1;
  return b;
}

RgbdFrame sample_frame(const RecordingMeta& m, int k) {
  RgbdFrame f;
  f.color = cv::Mat(m.color.height, m.color.width, CV_8UC3, cv::Scalar(10 * k, 20, 30));
  f.depth = cv::Mat(m.depth.height, m.depth.width, CV_16U, cv::Scalar(1000 + k));
  f.body_index = cv::Mat(m.depth.height, m.depth.width, CV_8U, cv::Scalar(kNoBody));
  f.body_index.at<uint8_t>(2, 3) = 5;
  f.bodies = {sample_body(0), sample_body(5)};
  FrameTruth t;
  PersonTruth p;
  p.identity = 3;
  p.tracking_id = 1003;
  p.body_index = 5;
  p.yaw_deg = -135.5;
  p.visible_fraction = 0.25;
  p.visible_pixels = 1;
  p.depth_box = {3, 2, 1, 1};
  p.top = "red top";
  p.bottom = "black trousers";
  p.accessories = {"hat"};
  p.top_bgr = {1, 2, 3};
  t.people.push_back(p);
  f.truth = t;
  return f;
}

TEST(Recording, WriteThenReadGivesTheSameFrames) {
  TempDir dir;
  const auto out = (dir / "rec").string();
  const RecordingMeta m = small_meta();
  {
    RecordingWriter w(out, m);
    for (int k = 0; k < 3; ++k) w.write(sample_frame(m, k));
    EXPECT_EQ(w.frame_count(), 3);
  }
  RecordingReader r(out);
  EXPECT_EQ(r.frame_count(), 3);
  EXPECT_EQ(r.meta().depth.width, 8);
  EXPECT_DOUBLE_EQ(r.meta().color.cx, 7.5);
  RgbdFrame f;
  int n = 0;
  while (r.read(f)) {
    EXPECT_EQ(f.index, n);
    EXPECT_DOUBLE_EQ(f.time_s, n / 30.0);
    EXPECT_EQ(f.color.at<cv::Vec3b>(0, 0)[0], 10 * n);
    EXPECT_EQ(f.depth.at<uint16_t>(1, 1), 1000 + n);
    EXPECT_EQ(f.body_index.at<uint8_t>(2, 3), 5);
    ASSERT_EQ(f.bodies.size(), 2u);
    EXPECT_EQ(f.bodies[0].tracking_id, 72057594037934994ULL);
    EXPECT_EQ(f.bodies[1].index, 5);
    EXPECT_FALSE(f.bodies[0].joints[idx(Joint::kHead)].orientation.has_value());
    EXPECT_NEAR(f.bodies[0].joints[3 - 1].orientation->y, std::sin(0.1), 1e-12);
    EXPECT_EQ(f.bodies[0].joints[idx(Joint::kHandTipLeft)].tracking_state, 1);
    ASSERT_TRUE(f.truth.has_value());
    EXPECT_EQ(f.truth->people[0].identity, 3);
    EXPECT_DOUBLE_EQ(f.truth->people[0].yaw_deg, -135.5);
    EXPECT_EQ(f.truth->people[0].top_bgr, cv::Vec3b(1, 2, 3));
    EXPECT_EQ(f.truth->people[0].accessories, std::vector<std::string>{"hat"});
    ++n;
  }
  EXPECT_EQ(n, 3);
}

TEST(Recording, JpegColourAndBodiesOnlyRecordings) {
  TempDir dir;
  RecordingMeta m = small_meta();
  m.color_format = "jpg";
  {
    RecordingWriter w((dir / "jpg").string(), m);
    w.write(sample_frame(m, 2));
  }
  EXPECT_TRUE(std::filesystem::exists(dir / "jpg" / "color" / "000000.jpg"));
  const RgbdFrame f = RecordingReader((dir / "jpg").string()).read_frame(0);
  EXPECT_NEAR(f.color.at<cv::Vec3b>(5, 5)[0], 20, 3);  // lossy
  m.streams = {};
  m.streams.bodies = true;
  {
    RecordingWriter w((dir / "bodies").string(), m);
    RgbdFrame b;
    b.bodies = {sample_body(3)};
    w.write(b);
    w.write(RgbdFrame{});
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "bodies" / "color"));
  RecordingReader r((dir / "bodies").string());
  EXPECT_EQ(r.frame_count(), 2);
  const RgbdFrame g = r.read_frame(0);
  EXPECT_TRUE(g.color.empty() && g.depth.empty() && g.body_index.empty() && !g.truth);
  EXPECT_EQ(g.bodies.at(0).index, 3);
  EXPECT_TRUE(r.read_frame(1).bodies.empty());
}

TEST(Recording, WriterRefusesWrongImagesAndANonEmptyDirectory) {
  TempDir dir;
  const RecordingMeta m = small_meta();
  RecordingWriter w((dir / "rec").string(), m);
  RgbdFrame f = sample_frame(m, 0);
  f.depth = cv::Mat(6, 8, CV_8U, cv::Scalar(1));
  EXPECT_TRUE(contains(input_error([&] { w.write(f); }), "depth image is 8-bit 1-channel, expected 16-bit"));
  f = sample_frame(m, 0);
  f.color = cv::Mat(10, 16, CV_8UC3);
  EXPECT_TRUE(contains(input_error([&] { w.write(f); }), "colour image is 16x10, intrinsics say 16x12"));
  f = sample_frame(m, 0);
  f.body_index.at<uint8_t>(4, 6) = 6;
  EXPECT_TRUE(contains(input_error([&] { w.write(f); }), "body index value 6 at (6, 4); expected 0..5 or 255"));
  f = sample_frame(m, 0);
  f.bodies[1].index = 0;
  EXPECT_TRUE(contains(input_error([&] { w.write(f); }), "bodies[1].index: slot 0 used twice"));
  f = sample_frame(m, 0);
  f.bodies[0].joints[4].orientation = Quaternion{0, 0, 0, 0};
  EXPECT_TRUE(contains(input_error([&] { w.write(f); }), "joints[4] (ShoulderLeft).orientation: quaternion is zero"));
  EXPECT_EQ(w.frame_count(), 0);
  EXPECT_THROW(RecordingWriter((dir / "rec").string(), m), UsageError);
}

json good_meta_json() { return to_json(small_meta()); }

std::string meta_error(const json& j) { return input_error([&] { meta_from_json(j, "m.json"); }); }

TEST(RecordingMeta, BrokenFieldsAreNamed) {
  json j = good_meta_json();
  EXPECT_NO_THROW(meta_from_json(j, "m.json"));
  j["version"] = 2;
  EXPECT_TRUE(contains(meta_error(j), "m.json: version: unknown version 2"));
  j = good_meta_json();
  j.erase("fps");
  EXPECT_EQ(meta_error(j), "m.json: fps: missing");
  j = good_meta_json();
  j["depth_intrinsics"]["fx"] = -3;
  EXPECT_EQ(meta_error(j), "m.json: depth_intrinsics: fx and fy must be positive");
  j = good_meta_json();
  j["color_intrinsics"]["width"] = "wide";
  EXPECT_EQ(meta_error(j), "m.json: color_intrinsics.width: expected an integer");
  j = good_meta_json();
  j["depth_to_color"]["rotation"] = {2, 0, 0, 0, 1, 0, 0, 0, 1};
  EXPECT_TRUE(contains(meta_error(j), "depth_to_color.rotation: not a rotation matrix"));
  j = good_meta_json();
  j["depth_to_color"]["translation"] = {0, 0};
  EXPECT_EQ(meta_error(j), "m.json: depth_to_color.translation: expected an array of 3 numbers");
  j = good_meta_json();
  j["streams"] = {"color", "infrared"};
  EXPECT_TRUE(contains(meta_error(j), "streams[1]: unknown stream \"infrared\""));
  j = good_meta_json();
  j["streams"] = {"bodyindex"};
  EXPECT_TRUE(contains(meta_error(j), "\"bodyindex\" needs \"depth\""));
  j = good_meta_json();
  j["format"] = "other";
  EXPECT_TRUE(contains(meta_error(j), "format: expected \"bodyrec-rgbd\""));
  j = good_meta_json();
  j["color_format"] = "bmp";
  EXPECT_TRUE(contains(meta_error(j), "color_format"));
  EXPECT_EQ(meta_error(json::array()), "m.json: expected a JSON object");
}

std::string bodies_error(const json& j) { return input_error([&] { bodies_from_json(j, "b.json"); }); }

TEST(RecordingBodies, BrokenFieldsAreNamed) {
  const json good = bodies_to_json({sample_body(0)});
  json j = good;
  j["bodies"][0]["joints"][2]["orientation"] = {1, 0, 0};
  EXPECT_EQ(bodies_error(j), "b.json: bodies[0].joints[2] (Neck).orientation: expected an array of 4 numbers");
  j = good;
  j["bodies"][0]["joints"][2]["orientation"] = {0, 0, 0, 0};
  EXPECT_TRUE(contains(bodies_error(j), "(Neck).orientation: quaternion is zero"));
  j = good;
  j["bodies"][0]["joints"][2]["position"][1] = "x";
  EXPECT_EQ(bodies_error(j), "b.json: bodies[0].joints[2] (Neck).position[1]: expected a number");
  j = good;
  j["bodies"][0]["joints"][5]["name"] = "Elbow";
  EXPECT_TRUE(contains(bodies_error(j), "joints[5] (ElbowLeft).name: expected \"ElbowLeft\""));
  j = good;
  j["bodies"][0]["joints"].erase(24);
  EXPECT_EQ(bodies_error(j), "b.json: bodies[0].joints: 24 joints, expected 25");
  j = good;
  j["bodies"][0]["index"] = 6;
  EXPECT_EQ(bodies_error(j), "b.json: bodies[0].index: 6 outside 0..5");
  j = good;
  j["bodies"][0]["tracking_id"] = -4;
  EXPECT_EQ(bodies_error(j), "b.json: bodies[0].tracking_id: expected a non-negative integer");
  j = good;
  j["bodies"][0]["joints"][0]["tracking_state"] = 3;
  EXPECT_TRUE(contains(bodies_error(j), "(SpineBase).tracking_state: 3 outside 0..2"));
  j = bodies_to_json({sample_body(0), sample_body(1), sample_body(2), sample_body(3), sample_body(4), sample_body(5)});
  j["bodies"].push_back(j["bodies"][0]);
  EXPECT_EQ(bodies_error(j), "b.json: bodies: 7 bodies, at most 6");
  EXPECT_EQ(bodies_error(json::object()), "b.json: bodies: missing");
}

std::string joints_error(const std::vector<Body>& bodies) {
  return input_error([&] { check_joint_positions(bodies, kinect2_depth_intrinsics(), "b.json"); });
}

// Tracked and inferred joints must be where the depth camera could see them; the limits are Z > 0,
// Z <= 20 m and the depth image widened by its own size (512x424: u in [-512, 1024), v in [-424, 848)).
TEST(RecordingBodies, JointsNoCameraCouldSeeAreNamed) {
  Body b = sample_body(0);  // joints at Z = 2.5 m, up to 2.4 m aside: u up to 606, inside the widened image
  EXPECT_NO_THROW(check_joint_positions({b}, kinect2_depth_intrinsics(), "b.json"));
  const auto with = [&](int joint, cv::Vec3d p, int state) {
    Body c = sample_body(0);
    c.joints[static_cast<size_t>(joint)].position = p;
    c.joints[static_cast<size_t>(joint)].tracking_state = state;
    return std::vector<Body>{sample_body(1), c};
  };
  EXPECT_EQ(joints_error(with(3, {0.1, 0.2, 0}, 2)),
            "b.json: bodies[1].joints[3] (Head).position: tracked joint at (0.1, 0.2, 0) m is at or behind the camera "
            "(Z must be > 0)");
  EXPECT_EQ(joints_error(with(4, {0.1, 0.2, -1.5}, 1)),
            "b.json: bodies[1].joints[4] (ShoulderLeft).position: inferred joint at (0.1, 0.2, -1.5) m is at or behind "
            "the camera (Z must be > 0)");
  EXPECT_EQ(joints_error(with(0, {0, 0, 20.5}, 2)),
            "b.json: bodies[1].joints[0] (SpineBase).position: tracked joint at (0, 0, 20.5) m is further than 20 m "
            "from the camera");
  EXPECT_NO_THROW(check_joint_positions(with(0, {0, 0, 20}, 2), kinect2_depth_intrinsics(), "b.json"));
  // u = 255.5 + 365.5 * X / Z: X = 5.2 at Z = 2 gives 1205.8, beyond 1024; X = 3.9 gives 968.2, inside.
  EXPECT_EQ(joints_error(with(7, {5.2, 0, 2}, 1)),
            "b.json: bodies[1].joints[7] (HandLeft).position: inferred joint at (5.2, 0, 2) m projects to pixel "
            "(1205.8, 211.5), more than the image's own size outside the 512x424 depth image");
  EXPECT_NO_THROW(check_joint_positions(with(7, {3.9, 0, 2}, 1), kinect2_depth_intrinsics(), "b.json"));
  EXPECT_NO_THROW(check_joint_positions(with(7, {-2.9, 0, 2}, 2), kinect2_depth_intrinsics(), "b.json"));  // u -274
  EXPECT_TRUE(contains(joints_error(with(7, {-4.3, 0, 2}, 2)), "projects to pixel (-530.325, 211.5)"));
  EXPECT_TRUE(contains(joints_error(with(7, {0, 5, 2}, 2)), "projects to pixel (255.5, -702.25)"));
  EXPECT_TRUE(contains(joints_error(with(7, {1e6, -1e6, 3}, 2)), "projects to pixel (1.21834e+08, 1.21834e+08)"));
  // Not tracked: any finite position passes (the sensor measured nothing there).
  EXPECT_NO_THROW(check_joint_positions(with(7, {1e6, -1e6, -3}, 0), kinect2_depth_intrinsics(), "b.json"));
}

TEST(Recording, WriterAndReaderRefuseJointsNoCameraCouldSee) {
  TempDir dir;
  const RecordingMeta m = small_meta();  // 8x6 depth image, fx 5: u = 3.5 + 5 X / Z
  RgbdFrame f = sample_frame(m, 0);
  f.bodies[1].joints[2].position = {0, 0, -1};
  {
    RecordingWriter w((dir / "w").string(), m);
    EXPECT_TRUE(contains(input_error([&] { w.write(f); }),
                         (dir / "w").string() + " frame 0 bodies: bodies[1].joints[2] (Neck).position: tracked joint at "
                                                "(0, 0, -1) m is at or behind the camera"));
    EXPECT_EQ(w.frame_count(), 0);
  }
  // A file written by something else is refused by the reader, naming the file.
  {
    RecordingWriter w((dir / "r").string(), m);
    w.write(sample_frame(m, 0));
  }
  const auto file = dir / "r" / "bodies" / "000000.json";
  json j = json::parse(bodyrec::testing::read_text(file));
  j["bodies"][0]["joints"][24]["position"] = {30, 0, 2};
  write_text(file, j.dump());
  EXPECT_EQ(input_error([&] { RecordingReader((dir / "r").string()).read_frame(0); }),
            file.string() + ": bodies[0].joints[24] (ThumbRight).position: tracked joint at (30, 0, 2) m projects to "
                            "pixel (78.5, 2.5), more than the image's own size outside the 8x6 depth image");
}

std::string truth_error(const json& j) { return input_error([&] { truth_from_json(j, "t.json"); }); }

TEST(RecordingTruth, BrokenFieldsAreNamed) {
  const json good = to_json(*sample_frame(small_meta(), 0).truth);
  EXPECT_EQ(truth_from_json(good, "t.json").people.size(), 1u);
  json j = good;
  j["people"][0]["yaw_deg"] = 270;
  EXPECT_EQ(truth_error(j), "t.json: people[0].yaw_deg: outside -180..180");
  j = good;
  j["people"][0]["visible_fraction"] = 1.5;
  EXPECT_EQ(truth_error(j), "t.json: people[0].visible_fraction: outside 0..1");
  j = good;
  j["people"][0]["body_index"] = 7;
  EXPECT_EQ(truth_error(j), "t.json: people[0].body_index: 7 outside -1..5");
  j = good;
  j["people"][0].erase("identity");
  EXPECT_EQ(truth_error(j), "t.json: people[0].identity: missing");
  j = good;
  j["people"][0]["top_rgb"] = {1, 2, 300};
  EXPECT_EQ(truth_error(j), "t.json: people[0].top_rgb[2]: 300 outside 0..255");
  j = good;
  j["people"].push_back(j["people"][0]);
  EXPECT_EQ(truth_error(j), "t.json: people[1].identity: identity 3 twice");
}

class BrokenRecording : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = (tmp_ / "rec").string();
    const RecordingMeta m = small_meta();
    RecordingWriter w(dir_, m);
    w.write(sample_frame(m, 0));
  }
  std::string read_error() {
    return input_error([&] { RecordingReader(dir_).read_frame(0); });
  }
  TempDir tmp_;
  std::string dir_;
};

TEST_F(BrokenRecording, MissingOrBadMeta) {
  std::filesystem::remove(dir_ + "/meta.json");
  EXPECT_EQ(read_error(), dir_ + "/meta.json: missing (not a bodyrec recording)");
  write_text(dir_ + "/meta.json", "{\"format\": ");
  EXPECT_TRUE(contains(read_error(), dir_ + "/meta.json: not valid JSON"));
  EXPECT_EQ(input_error([&] { RecordingReader(dir_ + "/nothing"); }), dir_ + "/nothing: not a recording directory");
}

TEST_F(BrokenRecording, WrongDepthTypeAndSize) {
  cv::imwrite(dir_ + "/depth/000000.png", cv::Mat(6, 8, CV_8U, cv::Scalar(9)));
  EXPECT_EQ(read_error(), dir_ + "/depth/000000.png: depth image is 8-bit 1-channel, expected 16-bit 1-channel");
  cv::imwrite(dir_ + "/depth/000000.png", cv::Mat(5, 8, CV_16U, cv::Scalar(9)));
  EXPECT_EQ(read_error(), dir_ + "/depth/000000.png: depth image is 8x5, intrinsics say 8x6");
  std::filesystem::remove(dir_ + "/depth/000000.png");
  EXPECT_EQ(read_error(), dir_ + "/depth/000000.png: missing");
  write_text(dir_ + "/depth/000000.png", "not a png");
  EXPECT_EQ(read_error(), dir_ + "/depth/000000.png: cannot decode image");
}

TEST_F(BrokenRecording, BodyIndexAboveFive) {
  cv::Mat bi(6, 8, CV_8U, cv::Scalar(kNoBody));
  bi.at<uint8_t>(1, 2) = 9;
  cv::imwrite(dir_ + "/bodyindex/000000.png", bi);
  EXPECT_EQ(read_error(), dir_ + "/bodyindex/000000.png: body index value 9 at (2, 1); expected 0..5 or 255");
}

TEST_F(BrokenRecording, BrokenBodiesAndTruthFiles) {
  write_text(dir_ + "/bodies/000000.json", "{\"bodies\": [{\"tracking_id\": 1}]}");
  EXPECT_EQ(read_error(), dir_ + "/bodies/000000.json: bodies[0].index: missing");
  write_text(dir_ + "/bodies/000000.json", "{\"bodies\": []}");
  write_text(dir_ + "/truth/000000.json", "[]");
  EXPECT_EQ(read_error(), dir_ + "/truth/000000.json: expected an object");
}

TEST(RecordingJson, NonFiniteQuaternionIsRejected) {
  json j = bodies_to_json({sample_body(0)});
  j["bodies"][0]["joints"][1]["orientation"][0] = std::numeric_limits<double>::infinity();  // dumps as null
  EXPECT_TRUE(contains(input_error([&] { bodies_from_json(json::parse(j.dump()), "b.json"); }), "orientation[0]: expected a number"));
}

// Fuzz finding (fuzz/regressions/recording_meta, recording_bodies): a number too large for a double made
// nlohmann throw out_of_range, which escaped as an untyped exception; now an InputError naming the file.
TEST(RecordingJson, FuzzNumberOverflowIsAnInputError) {
  EXPECT_EQ(input_error([] { parse_json_text("{\"fps\": 1e400}", "r/meta.json"); }),
            "r/meta.json: not valid JSON (number out of range)");
  EXPECT_TRUE(contains(input_error([] { parse_json_text("{\"fps\": 1", "r/meta.json"); }), "r/meta.json: not valid JSON (byte"));
}

}  // namespace
}  // namespace bodyrec
