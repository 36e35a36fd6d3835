// CVML/PETS XML, MOTChallenge text and imglab XML parsers: valid files and broken ones. Every broken
// file must give an InputError whose message names the file and the line, frame or field at fault.
#include <gtest/gtest.h>

#include "bodyrec/core/error.h"
#include "bodyrec/io/ground_truth.h"
#include "bodyrec/io/imglab_xml.h"
#include "test_support.h"

namespace bodyrec {
namespace {

using testing::TempDir;
using testing::write_text;

// Runs `parse` and returns the InputError message ("" and a test failure when nothing is thrown).
template <typename F>
std::string input_error(F parse) {
  try {
    parse();
  } catch (const InputError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected InputError, got: " << e.what();
    return "";
  }
  ADD_FAILURE() << "expected InputError, nothing thrown";
  return "";
}

const char* kCvml = R"(<?xml version="1.0"?>
<dataset>
  <frame number="0"><objectlist>
    <object id="9"><box h="80" w="30" xc="100" yc="200"/></object>
    <object id="15"><box h="90.5" w="32" xc="300" yc="260"/></object>
  </objectlist></frame>
  <frame number="1"><objectlist>
    <object id="9"><box h="80" w="30" xc="102" yc="201"/></object>
  </objectlist></frame>
  <frame number="2"><objectlist/></frame>
</dataset>
)";

TEST(Cvml, ReadsBoxesFromCentreAndSize) {
  TempDir dir;
  write_text(dir / "gt.xml", kCvml);
  const GroundTruth gt = read_cvml((dir / "gt.xml").string());
  ASSERT_EQ(gt.boxes.size(), 3u);
  EXPECT_EQ(gt.frame_count, 3);
  EXPECT_EQ(gt.boxes[0].id, 9);
  EXPECT_EQ(gt.boxes[0].frame, 0);
  EXPECT_EQ(gt.boxes[0].box, Box(85, 160, 30, 80));
  EXPECT_EQ(gt.boxes[1].box, Box(284, 214.75, 32, 90.5));
  EXPECT_EQ(gt.boxes[2].frame, 1);
  EXPECT_EQ(gt.by_frame().size(), 2u);
  EXPECT_EQ(read_ground_truth((dir / "gt.xml").string()).boxes.size(), 3u);  // dispatch by extension
}

TEST(Cvml, BrokenFilesGiveErrorsThatSayWhere) {
  TempDir dir;
  const std::string path = (dir / "bad.xml").string();
  auto error_for = [&](const std::string& text) {
    write_text(path, text);
    return input_error([&] { read_cvml(path); });
  };
  std::string m = error_for(std::string(kCvml).substr(0, 200));  // truncated
  EXPECT_NE(m.find(path), std::string::npos) << m;
  EXPECT_NE(m.find("line"), std::string::npos) << m;
  EXPECT_NE(m.find("malformed XML"), std::string::npos) << m;

  m = error_for("<annotations><frame number='0'/></annotations>");
  EXPECT_NE(m.find("<dataset>"), std::string::npos) << m;

  m = error_for("<dataset><frame number='4'><objectlist><object id='3'><box w='1' xc='1' yc='1'/></object>"
                "</objectlist></frame></dataset>");
  EXPECT_NE(m.find("frame 4"), std::string::npos) << m;
  EXPECT_NE(m.find("object 3"), std::string::npos) << m;
  EXPECT_NE(m.find("'h'"), std::string::npos) << m;

  m = error_for("<dataset><frame number='0'><objectlist><object id='3'><box h='abc' w='1' xc='1' yc='1'/>"
                "</object></objectlist></frame></dataset>");
  EXPECT_NE(m.find("'h' is not a finite number: 'abc'"), std::string::npos) << m;

  m = error_for("<dataset><frame number='0'><objectlist><object id='3'><box h='-5' w='1' xc='1' yc='1'/>"
                "</object></objectlist></frame></dataset>");
  EXPECT_NE(m.find("negative box size"), std::string::npos) << m;

  m = error_for("<dataset><frame><objectlist/></frame></dataset>");
  EXPECT_NE(m.find("'number'"), std::string::npos) << m;

  m = error_for("<dataset><frame number='0'><objectlist><object id='1'/></objectlist></frame></dataset>");
  EXPECT_NE(m.find("missing <box>"), std::string::npos) << m;

  m = error_for("<dataset/>");
  EXPECT_NE(m.find("no <frame>"), std::string::npos) << m;

  m = error_for("");
  EXPECT_NE(m.find("empty file"), std::string::npos) << m;

  m = input_error([&] { read_ground_truth((dir / "missing.xml").string()); });
  EXPECT_NE(m.find("missing.xml"), std::string::npos) << m;
}

TEST(Mot, ReadsGroundTruthWithIgnoredRowsAndOneBasedFrames) {
  TempDir dir;
  write_text(dir / "gt.txt",
             "1,1,912,484,97,109,0,7,1.0\r\n"   // confidence 0: ignored
             "1,2,1338,418,167,379,1,1,1.0\r\n"
             "\r\n"
             "2,2,1340,418,167,379,1,2,0.5\r\n"  // class 2 (person on vehicle): ignored
             "3,2,1342,418,167,379,1,1,0.5\r\n");
  const GroundTruth gt = read_ground_truth((dir / "gt.txt").string());
  ASSERT_EQ(gt.boxes.size(), 4u);
  EXPECT_EQ(gt.frame_count, 3);
  EXPECT_EQ(gt.boxes[0].frame, 0);
  EXPECT_TRUE(gt.boxes[0].ignore);
  EXPECT_FALSE(gt.boxes[1].ignore);
  EXPECT_TRUE(gt.boxes[2].ignore);
  EXPECT_EQ(gt.boxes[3].frame, 2);
  EXPECT_EQ(gt.boxes[1].box, Box(1338, 418, 167, 379));
}

TEST(Mot, ReadsResultsWithScores) {
  TempDir dir;
  write_text(dir / "res.txt", "1,-1,10.50,20.25,30,60,0.875000,-1,-1,-1\n2,4,11,21,30,60,-0.5,-1,-1,-1\n");
  const GroundTruth r = read_mot((dir / "res.txt").string(), false);
  ASSERT_EQ(r.boxes.size(), 2u);
  EXPECT_DOUBLE_EQ(r.boxes[0].score, 0.875);
  EXPECT_DOUBLE_EQ(r.boxes[1].score, -0.5);
  EXPECT_EQ(r.boxes[1].id, 4);
  EXPECT_FALSE(r.boxes[0].ignore);
  EXPECT_EQ(r.boxes[0].box, Box(10.5, 20.25, 30, 60));
}

TEST(Mot, BrokenRowsNameTheLineAndField) {
  TempDir dir;
  const std::string path = (dir / "bad.txt").string();
  auto error_for = [&](const std::string& text) {
    write_text(path, text);
    return input_error([&] { read_mot(path, true); });
  };
  std::string m = error_for("1,1,1,1,5,5\n2,1,1,1\n");
  EXPECT_NE(m.find(path + ": line 2"), std::string::npos) << m;
  EXPECT_NE(m.find("at least 6"), std::string::npos) << m;
  m = error_for("1,1,x,1,5,5\n");
  EXPECT_NE(m.find("line 1: field 'x'"), std::string::npos) << m;
  m = error_for("0,1,1,1,5,5\n");
  EXPECT_NE(m.find("1-based"), std::string::npos) << m;
  m = error_for("1,1,1,1,-5,5\n");
  EXPECT_NE(m.find("negative box size"), std::string::npos) << m;
  m = error_for("1,1,1,1,5,nan\n");
  EXPECT_NE(m.find("field 'h'"), std::string::npos) << m;
  m = input_error([&] { read_mot((dir / "none.txt").string(), true); });
  EXPECT_NE(m.find("none.txt"), std::string::npos) << m;
}

TEST(Imglab, RoundTripKeepsBoxesLabelsIgnoreAndParts) {
  TempDir dir;
  ImglabDataset d;
  d.name = "bodies";
  d.comment = "made by a test";
  ImglabImage image{"images/a.png", {}};
  ImglabBox box;
  box.box = Box(10, 20, 30, 60);
  box.label = "body_detected";
  box.parts = {{"01", {12, 25}}, {"00", {11, 21}}};
  image.boxes.push_back(box);
  ImglabBox ignored;
  ignored.box = Box(100, 100, 5, 5);
  ignored.ignore = true;
  image.boxes.push_back(ignored);
  d.images.push_back(image);
  const std::string path = (dir / "set.xml").string();
  write_imglab(d, path);

  const ImglabDataset back = read_imglab(path);
  EXPECT_EQ(back.name, "bodies");
  ASSERT_EQ(back.images.size(), 1u);
  EXPECT_EQ(back.images[0].file, "images/a.png");
  ASSERT_EQ(back.images[0].boxes.size(), 2u);
  EXPECT_EQ(back.images[0].boxes[0].box, Box(10, 20, 30, 60));
  EXPECT_EQ(back.images[0].boxes[0].label, "body_detected");
  EXPECT_FALSE(back.images[0].boxes[0].ignore);
  EXPECT_TRUE(back.images[0].boxes[1].ignore);
  const auto points = ordered_parts(back.images[0].boxes[0], "box");
  ASSERT_EQ(points.size(), 2u);
  EXPECT_EQ(points[0], cv::Point2d(11, 21));
  EXPECT_EQ(points[1], cv::Point2d(12, 25));
  EXPECT_EQ(resolve_image_path(path, "images/a.png"), (dir / "images/a.png").string());
  EXPECT_EQ(resolve_image_path(path, "/abs/b.png"), "/abs/b.png");
}

TEST(Imglab, BrokenFilesGiveErrorsThatSayWhere) {
  TempDir dir;
  const std::string path = (dir / "bad.xml").string();
  auto error_for = [&](const std::string& text) {
    write_text(path, text);
    return input_error([&] { read_imglab(path); });
  };
  std::string m = error_for("<dataset><images><image file='a.png'><box top='1' left='2' width='3'");
  EXPECT_NE(m.find("malformed XML"), std::string::npos) << m;
  m = error_for("<dataset><images><image><box top='1' left='2' width='3' height='4'/></image></images></dataset>");
  EXPECT_NE(m.find("image 0: missing attribute 'file'"), std::string::npos) << m;
  m = error_for("<dataset><images><image file='a.png'><box top='1' width='3' height='4'/></image></images></dataset>");
  EXPECT_NE(m.find("image a.png: box 0: missing attribute 'left'"), std::string::npos) << m;
  m = error_for("<dataset><images><image file='a.png'><box top='1' left='1' width='-3' height='4'/></image>"
                "</images></dataset>");
  EXPECT_NE(m.find("negative width"), std::string::npos) << m;
  m = error_for("<dataset><images><image file='a.png'><box top='1' left='1' width='3' height='4'>"
                "<part name='00' y='3'/></box></image></images></dataset>");
  EXPECT_NE(m.find("part 00: missing attribute 'x'"), std::string::npos) << m;
  m = error_for("<images/>");
  EXPECT_NE(m.find("not an imglab dataset"), std::string::npos) << m;

  ImglabBox box;
  box.parts = {{"00", {0, 0}}, {"02", {1, 1}}};
  m = input_error([&] { ordered_parts(box, "img box 0"); });
  EXPECT_NE(m.find("img box 0: landmark 1 is missing"), std::string::npos) << m;
  box.parts = {{"00", {0, 0}}, {"0", {1, 1}}};
  m = input_error([&] { ordered_parts(box, "b"); });
  EXPECT_NE(m.find("appears twice"), std::string::npos) << m;
  box.parts = {{"head", {0, 0}}};
  m = input_error([&] { ordered_parts(box, "b"); });
  EXPECT_NE(m.find("'head' is not a landmark number"), std::string::npos) << m;
}

}  // namespace
}  // namespace bodyrec
