// The bad-input table of docs/reliability.md, row by row: each broken input gives the documented exit code,
// one line on stderr naming the file (and frame or field), and the output of the frames before it intact.
#include <unistd.h>

#include <array>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "test_support.h"

namespace fs = std::filesystem;

namespace bodyrec::testing {
namespace {

// 4 frames, 2 people (seed 3, group): frame 0 has no body, frames 1 and 2 two, frame 3 one. Tests break
// frame 2 of a copy and check frames 0 and 1 were written.
fs::path recording_copy(const TempDir& dir, const std::string& name = "rec") {
  const fs::path& made = synth_recording({"--frames", "4", "--people", "2", "--seed", "3", "--scenario", "group"});
  const fs::path copy = dir / name;
  fs::copy(made, copy, fs::copy_options::recursive);
  return copy;
}

// `jsonl` holds exactly `frames` complete JSON lines for frames 0, 1, ...
void expect_frames_written(const fs::path& jsonl, int frames) {
  const std::string text = read_text(jsonl);
  if (frames > 0) {
    EXPECT_EQ(text.back(), '\n') << "a partial last line";
  }
  const auto lines = lines_of(text);
  ASSERT_EQ(static_cast<int>(lines.size()), frames) << text;
  for (int i = 0; i < frames; ++i) EXPECT_EQ(nlohmann::json::parse(lines[i])["frame"].get<int>(), i);
}

// A noisy picture, so its PNG and JPEG files are large and cutting them in half cuts the image data.
cv::Mat noise_image() {
  cv::Mat image(120, 160, CV_8UC3);
  cv::RNG(7).fill(image, cv::RNG::UNIFORM, 0, 256);
  return image;
}

void write_first_half(const fs::path& from, const fs::path& to) {
  const std::string bytes = read_text(from);
  write_text(to, bytes.substr(0, bytes.size() / 2));
}

RunResult detect(const fs::path& input, const fs::path& jsonl) {
  return run_bodyrec({"detect", input.string(), "--preset", "thesis", "--levels", "1", "--jsonl", jsonl.string(), "-q"});
}

// Root reads a file whatever its mode, so as root the commands run as user nobody (setpriv, util-linux),
// in a directory nobody owns. Empty when not root.
std::vector<std::string> unprivileged_prefix() {
  if (::geteuid() != 0) return {};
  return {"setpriv", "--reuid=65534", "--regid=65534", "--clear-groups", "--"};
}

TEST(BadInput, UnreadableFilesNameTheFileAndKeepEarlierFrames) {
  const std::vector<std::string> as = unprivileged_prefix();
  if (!as.empty() && run_bodyrec({"--version"}, as).exit_code != 0)
    GTEST_SKIP() << "running as root and user nobody cannot run the bodyrec binary (chmod 000 does not stop "
                    "root from reading a file, so this row needs another user: make the build directory readable)";
  TempDir dir;
  if (!as.empty()) {
    ASSERT_EQ(::chown(dir.path().c_str(), 65534, 65534), 0);
  }
  cv::imwrite((dir / "a.png").string(), noise_image());
  cv::imwrite((dir / "b.png").string(), noise_image());
  fs::permissions(dir / "b.png", fs::perms::none);
  RunResult r = run_bodyrec({"detect", dir.path().string(), "--preset", "thesis", "--levels", "1", "--jsonl",
                             (dir / "d.jsonl").string(), "-q"}, as);
  expect_one_line_error(r, 3, (dir / "b.png").string() + ": cannot read (Permission denied) (frame 1)");
  expect_frames_written(dir / "d.jsonl", 1);

  const fs::path rec = recording_copy(dir);
  fs::permissions(rec / "depth" / "000002.png", fs::perms::none);
  r = run_bodyrec({"segment", rec.string(), "--jsonl", (dir / "s.jsonl").string()}, as);
  expect_one_line_error(r, 3, (rec / "depth" / "000002.png").string() + ": cannot read (Permission denied)");
  expect_frames_written(dir / "s.jsonl", 2);
  fs::permissions(rec / "meta.json", fs::perms::none);
  r = run_bodyrec({"orient", rec.string()}, as);
  expect_one_line_error(r, 3, (rec / "meta.json").string());
}

TEST(BadInput, MissingAndZeroByteFilesNameTheFile) {
  TempDir dir;
  expect_one_line_error(detect(dir / "none.avi", dir / "d.jsonl"), 3, "input not found: " + (dir / "none.avi").string());
  for (const char* command : {"orient", "segment", "contour", "greenscreen"}) {
    std::vector<std::string> args = {command, (dir / "none").string()};
    if (std::string(command) == "greenscreen") args.insert(args.end(), {"--out", (dir / "cut").string()});
    expect_one_line_error(run_bodyrec(args), 3, (dir / "none").string() + ": not a recording directory");
  }
  write_text(dir / "zero.png", "");
  expect_one_line_error(detect(dir / "zero.png", dir / "d.jsonl"), 3, (dir / "zero.png").string() + ": empty file");
  write_text(dir / "zero.avi", "");
  expect_one_line_error(detect(dir / "zero.avi", dir / "d.jsonl"), 3,
                        "video file is empty: " + (dir / "zero.avi").string());

  // In a recording: frames 0 and 1 are written before frame 2's broken file stops the run.
  const fs::path rec = recording_copy(dir);
  write_text(rec / "depth" / "000002.png", "");
  RunResult r = run_bodyrec({"segment", rec.string(), "--jsonl", (dir / "s.jsonl").string()});
  expect_one_line_error(r, 3, (rec / "depth" / "000002.png").string() + ": empty file");
  expect_frames_written(dir / "s.jsonl", 2);
  fs::remove(rec / "depth" / "000002.png");
  r = run_bodyrec({"segment", rec.string(), "--jsonl", (dir / "s.jsonl").string()});
  expect_one_line_error(r, 3, (rec / "depth" / "000002.png").string() + ": missing");
  expect_frames_written(dir / "s.jsonl", 2);
  const fs::path rec2 = recording_copy(dir, "rec2");
  write_text(rec2 / "bodies" / "000002.json", "");
  r = run_bodyrec({"orient", rec2.string(), "--jsonl", (dir / "o.jsonl").string()});
  expect_one_line_error(r, 3, (rec2 / "bodies" / "000002.json").string() + ": not valid JSON");
  expect_frames_written(dir / "o.jsonl", 2);
  write_text(rec2 / "meta.json", "");
  expect_one_line_error(run_bodyrec({"orient", rec2.string()}), 3, (rec2 / "meta.json").string() + ": not valid JSON");

  // A zero-byte ground-truth file has no frame to score: an input error, not a score of nothing.
  if (fs::exists(vtest_path())) {
    write_text(dir / "gt.txt", "");
    r = run_bodyrec({"eval", "track", "--source", vtest_path().string(), "--gt", (dir / "gt.txt").string(),
                     "--max-frames", "1", "--preset", "thesis", "--levels", "1"});
    expect_one_line_error(r, 3, (dir / "gt.txt").string());
  }
}

TEST(BadInput, TruncatedPngAndJpegAreOneLineErrorsAfterTheFramesBefore) {
  for (const std::string ext : {".png", ".jpg"}) {
    SCOPED_TRACE(ext);
    TempDir dir;
    fs::create_directories(dir / "in");
    cv::imwrite((dir / "in" / ("a" + ext)).string(), noise_image());
    cv::imwrite((dir / "whole" ).string() + ext, noise_image());
    write_first_half((dir / "whole").string() + ext, dir / "in" / ("b" + ext));
    const RunResult r = detect(dir / "in", dir / "d.jsonl");
    // One line: neither libpng's "Read Error" nor libjpeg's "Premature end of JPEG file" gets through, and a
    // truncated JPEG, which OpenCV decodes with grey below the cut, is refused.
    expect_one_line_error(r, 3,
                          (dir / "in" / ("b" + ext)).string() + ": truncated " + (ext == ".png" ? "PNG" : "JPEG") +
                              " file");
    EXPECT_TRUE(contains(r.err, "(frame 1)")) << r.err;
    expect_frames_written(dir / "d.jsonl", 1);
  }
  // A truncated depth PNG in a recording.
  TempDir dir;
  const fs::path rec = recording_copy(dir);
  write_first_half(rec / "depth" / "000002.png", rec / "depth" / "000002.png");
  const RunResult r = run_bodyrec({"segment", rec.string(), "--jsonl", (dir / "s.jsonl").string()});
  expect_one_line_error(r, 3, (rec / "depth" / "000002.png").string() + ": truncated PNG file");
  expect_frames_written(dir / "s.jsonl", 2);
}

// A PNG damaged in the middle (one byte of its image data changed, length kept): bodyrec's one line, not
// libpng's "IDAT: CRC error" before it.
TEST(BadInput, APngCorruptInTheMiddleIsAOneLineError) {
  TempDir dir;
  fs::create_directories(dir / "in");
  cv::imwrite((dir / "in" / "a.png").string(), noise_image());
  std::string bytes = read_text(dir / "in" / "a.png");
  const size_t idat = bytes.find("IDAT");
  ASSERT_NE(idat, std::string::npos);
  bytes[idat + 100] = static_cast<char>(bytes[idat + 100] ^ 0x5a);
  write_text(dir / "in" / "b.png", bytes);
  const RunResult r = detect(dir / "in", dir / "d.jsonl");
  expect_one_line_error(r, 3,
                        (dir / "in" / "b.png").string() + ": corrupt PNG file (chunk IDAT at byte " +
                            std::to_string(idat - 4) + " fails its CRC check) (frame 1)");
  expect_frames_written(dir / "d.jsonl", 1);
}

// The fHOG model file has one name in every command (--detector-model; --model where it means nothing else).
TEST(BadInput, AMissingDetectorModelIsNamedByEveryCommand) {
  TempDir dir;
  cv::imwrite((dir / "a.png").string(), noise_image());
  const std::string model = (dir / "none.svm").string(), image = (dir / "a.png").string();
  for (const char* command : {"detect", "track", "groups", "landmark"})
    for (const char* flag : {"--detector-model", "--model"})
      expect_one_line_error(run_bodyrec({command, image, flag, model}), 3, "cannot read detector model " + model);
  expect_one_line_error(run_bodyrec({"reid", image, "--detector", "hog", "--detector-model", model, "--gallery",
                                     (dir / "g.db").string()}),
                        3, "cannot read detector model " + model);
}

TEST(BadInput, ImageWhereAVideoOrRecordingIsExpected) {
  TempDir dir;
  cv::imwrite((dir / "frame.png").string(), noise_image());
  fs::copy_file(dir / "frame.png", dir / "clip.avi");
  // FFmpeg reads a PNG as a one-frame video: processed, one JSON line.
  const RunResult r = detect(dir / "clip.avi", dir / "d.jsonl");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  expect_frames_written(dir / "d.jsonl", 1);
  // Commands that read recordings refuse it, naming it.
  for (const char* command : {"orient", "segment", "contour"})
    expect_one_line_error(run_bodyrec({command, (dir / "frame.png").string()}), 3,
                          (dir / "frame.png").string() + ": not a recording directory");
  expect_one_line_error(run_bodyrec({"eval", "segment", (dir / "frame.png").string()}), 3,
                        (dir / "frame.png").string() + ": not a recording directory");
}

TEST(BadInput, DepthOfTheWrongTypeOrSizeNamesTheFrameFile) {
  TempDir dir;
  const fs::path rec = recording_copy(dir);
  const fs::path depth = rec / "depth" / "000002.png";
  cv::imwrite(depth.string(), cv::Mat(424, 512, CV_8U, cv::Scalar(30)));
  RunResult r = run_bodyrec({"segment", rec.string(), "--jsonl", (dir / "s.jsonl").string()});
  expect_one_line_error(r, 3, depth.string() + ": depth image is 8-bit 1-channel, expected 16-bit 1-channel");
  expect_frames_written(dir / "s.jsonl", 2);
  cv::imwrite(depth.string(), cv::Mat(212, 256, CV_16U, cv::Scalar(3000)));
  r = run_bodyrec({"segment", rec.string(), "--jsonl", (dir / "s.jsonl").string()});
  expect_one_line_error(r, 3, depth.string() + ": depth image is 256x212, intrinsics say 512x424");
  expect_frames_written(dir / "s.jsonl", 2);
}

TEST(BadInput, ZeroNanAndInfiniteQuaternionsNameTheFileAndField) {
  TempDir dir;
  const fs::path rec = recording_copy(dir);
  const fs::path bodies = rec / "bodies" / "000002.json";
  const nlohmann::json good = nlohmann::json::parse(read_text(bodies));
  const auto run = [&] { return run_bodyrec({"orient", rec.string(), "--jsonl", (dir / "o.jsonl").string()}); };

  nlohmann::json j = good;
  j["bodies"][1]["joints"][1]["orientation"] = {0, 0, 0, 0};
  write_text(bodies, j.dump());
  expect_one_line_error(run(), 3, bodies.string() + ": bodies[1].joints[1] (SpineMid).orientation: quaternion is zero");
  expect_frames_written(dir / "o.jsonl", 2);

  // JSON has no NaN or infinity: a writer that prints them makes the file invalid JSON; an overflowing
  // number is out of range. Both name the file.
  std::string text = good.dump();
  const std::string first_orientation = "\"orientation\":[";
  const size_t at = text.find(first_orientation) + first_orientation.size();
  write_text(bodies, text.substr(0, at) + "NaN," + text.substr(text.find(',', at) + 1));
  expect_one_line_error(run(), 3, bodies.string() + ": not valid JSON");
  expect_frames_written(dir / "o.jsonl", 2);
  write_text(bodies, text.substr(0, at) + "1e999," + text.substr(text.find(',', at) + 1));
  expect_one_line_error(run(), 3, bodies.string() + ": not valid JSON (number out of range)");
  expect_frames_written(dir / "o.jsonl", 2);
}

TEST(BadInput, BodyIndexAboveFiveNamesThePixel) {
  TempDir dir;
  const fs::path rec = recording_copy(dir);
  const fs::path index = rec / "bodyindex" / "000002.png";
  cv::Mat bi = cv::imread(index.string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(bi.type(), CV_8UC1);
  bi.at<uint8_t>(100, 200) = 9;
  cv::imwrite(index.string(), bi);
  RunResult r = run_bodyrec({"contour", rec.string(), "--jsonl", (dir / "c.jsonl").string()});
  expect_one_line_error(r, 3, index.string() + ": body index value 9 at (200, 100); expected 0..5 or 255");
  expect_frames_written(dir / "c.jsonl", 2);
  r = run_bodyrec({"eval", "segment", rec.string()});
  expect_one_line_error(r, 3, index.string() + ": body index value 9 at (200, 100)");
  // The same in the skeletons: a body slot above 5.
  const fs::path bodies = recording_copy(dir, "rec2") / "bodies" / "000002.json";
  nlohmann::json j = nlohmann::json::parse(read_text(bodies));
  j["bodies"][1]["index"] = 6;
  write_text(bodies, j.dump());
  r = run_bodyrec({"orient", (dir / "rec2").string(), "--jsonl", (dir / "o.jsonl").string()});
  expect_one_line_error(r, 3, bodies.string() + ": bodies[1].index: 6 outside 0..5");
  expect_frames_written(dir / "o.jsonl", 2);
}

// Skeleton joints nowhere a depth camera could see them (a million metres aside, at or behind the camera,
// 1e300 m away): the body file is broken like one with a zero quaternion, an input error naming the file,
// the body and the joint, after the frames before it were written. Every command that reads the
// recording stops the same way. Joints marked not tracked (0) carry no measurement and are not checked.
TEST(BadInput, JointsFarOutsideTheFrameAreInputErrorsNamingTheJoint) {
  TempDir dir;
  const fs::path rec = recording_copy(dir);
  const fs::path bodies = rec / "bodies" / "000002.json";
  const nlohmann::json good = nlohmann::json::parse(read_text(bodies));
  const nlohmann::json meta = nlohmann::json::parse(read_text(rec / "meta.json"));
  ASSERT_EQ(meta["depth_intrinsics"]["width"], 512);  // the messages below are for Kinect v2 intrinsics
  ASSERT_EQ(meta["depth_intrinsics"]["fx"], 365.5);
  const std::string joint = bodies.string() + ": bodies[0].joints[0] (SpineBase).position: tracked joint at ";
  const std::vector<std::pair<std::array<double, 3>, std::string>> cases = {
      {{1e6, -1e6, 3}, "(1e+06, -1e+06, 3) m projects to pixel (1.21834e+08, 1.21834e+08), more than the image's "
                       "own size outside the 512x424 depth image"},
      {{0.5, 0.2, 0}, "(0.5, 0.2, 0) m is at or behind the camera (Z must be > 0)"},
      {{0.5, 0.2, -2}, "(0.5, 0.2, -2) m is at or behind the camera (Z must be > 0)"},
      {{1e300, -1e300, 1e300}, "(1e+300, -1e+300, 1e+300) m is further than 20 m from the camera"},
  };
  const auto broken = [&](const std::array<double, 3>& place, int state) {
    nlohmann::json j = good;
    for (auto& jt : j["bodies"][0]["joints"]) {
      jt["position"] = place;
      jt["tracking_state"] = state;
    }
    write_text(bodies, j.dump());
  };
  for (const auto& [place, what] : cases) {
    SCOPED_TRACE(what);
    broken(place, 2);
    const std::string message = joint + what;
    RunResult r = run_bodyrec({"orient", rec.string(), "--jsonl", (dir / "o.jsonl").string(), "-q"});
    expect_one_line_error(r, 3, message);
    expect_frames_written(dir / "o.jsonl", 2);
    r = run_bodyrec({"contour", rec.string(), "--jsonl", (dir / "c.jsonl").string()});
    expect_one_line_error(r, 3, message);
    expect_frames_written(dir / "c.jsonl", 2);
    expect_one_line_error(run_bodyrec({"eval", "orient", rec.string()}), 3, message);
    fs::remove_all(dir / "cut");
    r = run_bodyrec({"greenscreen", rec.string(), "--out", (dir / "cut").string()});
    expect_one_line_error(r, 3, message);
    EXPECT_TRUE(fs::exists(dir / "cut" / "000001_body0.png"));
    EXPECT_FALSE(fs::exists(dir / "cut" / "000002_body0.png"));
    r = run_bodyrec({"reid", rec.string(), "--gallery", (dir / "g.db").string(), "--jsonl",
                     (dir / "r.jsonl").string(), "-q"});
    expect_one_line_error(r, 3, message);
    expect_frames_written(dir / "r.jsonl", 2);
  }
  // An inferred joint says "inferred"; the first bad joint is the one named.
  nlohmann::json j = good;
  j["bodies"][1]["joints"][7]["position"] = {0.5, 0.2, -2};
  j["bodies"][1]["joints"][7]["tracking_state"] = 1;
  write_text(bodies, j.dump());
  expect_one_line_error(run_bodyrec({"orient", rec.string()}), 3,
                        bodies.string() + ": bodies[1].joints[7] (HandLeft).position: inferred joint at (0.5, 0.2, -2) m "
                                          "is at or behind the camera");
  // The same positions on joints marked not tracked: nothing was measured there, the frame is processed.
  broken({1e6, -1e6, 3}, 0);
  const RunResult r = run_bodyrec({"orient", rec.string(), "--jsonl", (dir / "o.jsonl").string(), "-q"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  expect_frames_written(dir / "o.jsonl", 4);
}

// 500 ground-truth people in frame 1, none in frame 2, one in frame 3 (MOT frames are 1-based). The tracker
// side (500 detections, then none) is MultiTracker.FiveHundredDetectionsThenNoneKeepOneTrackPerPerson.
TEST(BadInput, FiveHundredAndZeroGroundTruthBoxesInAFrameAreScored) {
  if (!fs::exists(vtest_path())) GTEST_SKIP() << "vtest.avi missing (opencv-doc)";
  TempDir dir;
  std::string gt;
  for (int i = 0; i < 500; ++i)
    gt += "1," + std::to_string(i + 1) + "," + std::to_string(i % 25 * 30) + "," + std::to_string(i / 25 * 28) +
          ",28,26,1,1,1\n";
  gt += "3,7,300,200,40,100,1,1,1\n";
  write_text(dir / "gt.txt", gt);
  const RunResult r = run_bodyrec({"eval", "track", "--source", vtest_path().string(), "--gt", (dir / "gt.txt").string(),
                                   "--max-frames", "3", "--preset", "thesis", "--levels", "1", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "ground truth  501 boxes")) << r.out;
  const auto j = last_json_line(r.out);
  EXPECT_EQ(j["frames"].get<int>(), 3);
  // No track is confirmed before the third frame (3 hits), so all 500 of frame 1 are missed; frame 3's box
  // may be matched.
  EXPECT_GE(j["fn"].get<int>(), 500);
  EXPECT_LE(j["fn"].get<int>(), 501);
}

// Ground truth with nothing in the frames processed (another video's file, or the wrong frames) is an input
// error, not a score of 0 that reads as a detector or tracker that found nobody.
TEST(BadInput, GroundTruthOutsideTheFramesProcessedIsAnInputError) {
  if (!fs::exists(vtest_path())) GTEST_SKIP() << "vtest.avi missing (opencv-doc)";
  TempDir dir;
  const std::string gt = (dir / "gt.txt").string(), roles = (dir / "roles.csv").string(), v = vtest_path().string();
  write_text(gt, "500,1,10,10,30,90,1,1,1\n");
  write_text(roles, "frame,x,y,w,h,role\n5000,1,2,3,4,leader\n");
  expect_one_line_error(run_bodyrec({"eval", "detect", "--source", v, "--gt", gt, "--max-frames", "2", "--preset",
                                     "thesis", "--levels", "1", "-q"}),
                        3, gt + ": no ground-truth box in the 2 frames processed");
  expect_one_line_error(run_bodyrec({"eval", "track", "--source", v, "--gt", gt, "--max-frames", "2", "--preset",
                                     "thesis", "--levels", "1", "-q"}),
                        3, gt + ": no ground-truth box in the 2 frames processed");
  expect_one_line_error(run_bodyrec({"eval", "roles", "--source", v, "--gt", roles, "--max-frames", "2", "-q"}), 3,
                        roles + ": no labelled box in the 2 frames processed (its frames are 5000-5000)");
}

// A frame of another size than the first in an image folder: the error names that file.
TEST(BadInput, AFrameOfAnotherSizeNamesItsFile) {
  TempDir dir;
  fs::create_directories(dir / "frames");
  for (int i = 0; i < 3; ++i)
    cv::imwrite((dir / "frames" / ("00" + std::to_string(i) + ".png")).string(),
                cv::Mat(i == 2 ? 100 : 90, 120, CV_8UC3, cv::Scalar(40 * i, 90, 160)));
  const std::string odd = (dir / "frames" / "002.png").string();
  expect_one_line_error(run_bodyrec({"groups", (dir / "frames").string(), "-q", "--jsonl", (dir / "g.jsonl").string()}),
                        3, odd + ": motion: frame size changed");
  expect_frames_written(dir / "g.jsonl", 2);
}

}  // namespace
}  // namespace bodyrec::testing
