// CVML/PETS XML and MOTChallenge text ground truth: valid files and broken ones. Every broken file must
// give an InputError whose message names the file and the line, frame or field at fault.
#include "bodyrec/io/ground_truth.h"

#include <filesystem>

#include <gtest/gtest.h>

#include "bodyrec/core/error.h"
#include "test_support.h"

namespace bodyrec {
namespace {

using testing::TempDir;
using testing::write_text;

using testing::contains;
using testing::input_error;

// Two frames, three objects; PETS writes the attributes in this (h, w, xc, yc) order.
const char* kCvml = R"(<?xml version="1.0" encoding="utf-8"?>
<dataset name="test">
  <frame number="0">
    <objectlist>
      <object id="9"><box h="80" w="30" xc="100" yc="200"/></object>
      <object id="15"><box h="90.5" w="32" xc="300" yc="260"/></object>
    </objectlist>
  </frame>
  <frame number="1">
    <objectlist>
      <object id="9"><box h="80" w="30" xc="102" yc="201"/></object>
    </objectlist>
  </frame>
</dataset>
)";

// A CVML file with one object whose <box> has the given attributes, in frame `frame`.
std::string one_box(const std::string& box_attributes, int frame = 0) {
  return "<dataset><frame number='" + std::to_string(frame) + "'><objectlist><object id='3'><box " +
         box_attributes + "/></object></objectlist></frame></dataset>";
}

// ---- CVML -------------------------------------------------------------------------------------------

TEST(Cvml, ReadsBoxesFromCentreAndSize) {
  TempDir dir;
  write_text(dir / "gt.xml", kCvml);
  const GroundTruth gt = read_cvml((dir / "gt.xml").string());
  ASSERT_EQ(gt.boxes.size(), 3u);
  EXPECT_EQ(gt.frame_count, 2);
  EXPECT_EQ(gt.boxes[0].frame, 0);
  EXPECT_EQ(gt.boxes[0].id, 9);
  EXPECT_EQ(gt.boxes[0].box, Box(85, 160, 30, 80));  // xc - w/2, yc - h/2
  EXPECT_EQ(gt.boxes[1].id, 15);
  EXPECT_EQ(gt.boxes[1].box, Box(284, 214.75, 32, 90.5));
  EXPECT_EQ(gt.boxes[2].frame, 1);
  EXPECT_EQ(gt.boxes[2].id, 9);
  EXPECT_EQ(gt.boxes[2].box, Box(87, 161, 30, 80));
  for (const auto& b : gt.boxes) {
    EXPECT_DOUBLE_EQ(b.score, 1.0);
    EXPECT_FALSE(b.ignore);
  }
  const auto frames = gt.by_frame();
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames.at(0).size(), 2u);
  EXPECT_EQ(frames.at(1).size(), 1u);
}

TEST(Cvml, EmptyFramesCountTowardsFrameCount) {
  TempDir dir;
  write_text(dir / "gt.xml",
             "<dataset><frame number='0'><objectlist/></frame><frame number='1'/>"
             "<frame number='6'><objectlist><object id='2'><box h='10' w='4' xc='2' yc='5'/></object>"
             "</objectlist></frame><frame number='7'><objectlist/></frame></dataset>");
  const GroundTruth gt = read_cvml((dir / "gt.xml").string());
  EXPECT_EQ(gt.frame_count, 8);
  ASSERT_EQ(gt.boxes.size(), 1u);
  EXPECT_EQ(gt.boxes[0].frame, 6);
  EXPECT_EQ(gt.boxes[0].box, Box(0, 0, 4, 10));
  EXPECT_EQ(gt.by_frame().size(), 1u);
}

class CvmlBroken : public ::testing::Test {
 protected:
  std::string error_for(const std::string& text) {
    write_text(path, text);
    EXPECT_THROW(read_cvml(path), InputError);
    return input_error([&] { read_cvml(path); });
  }
  TempDir dir;
  const std::string path = (dir / "bad.xml").string();
};

TEST_F(CvmlBroken, TruncatedXmlNamesFileAndLine) {
  const std::string text = kCvml;
  const auto cut = text.find("<frame number=\"1\">");  // line 9; the file stops in the middle of it
  const std::string m = error_for(text.substr(0, cut + 10));
  EXPECT_TRUE(contains(m, path)) << m;
  EXPECT_TRUE(contains(m, "line 9")) << m;
  EXPECT_TRUE(contains(m, "malformed XML")) << m;
}

TEST_F(CvmlBroken, UnclosedRootNamesFile) {
  const std::string text = kCvml;
  const std::string m = error_for(text.substr(0, text.find("</dataset>")));
  EXPECT_TRUE(contains(m, path)) << m;
  EXPECT_TRUE(contains(m, "line")) << m;
}

TEST_F(CvmlBroken, WrongRootTag) {
  const std::string m = error_for("<annotations><frame number='0'/></annotations>");
  EXPECT_TRUE(contains(m, path)) << m;
  EXPECT_TRUE(contains(m, "no <dataset> root element")) << m;
}

TEST_F(CvmlBroken, MissingAttributeNamesFrameObjectAndField) {
  std::string m = error_for(one_box("w='1' xc='1' yc='1'", 4));
  EXPECT_TRUE(contains(m, path + ": frame 4: object 3: missing attribute 'h'")) << m;
  m = error_for(one_box("h='1' w='1' yc='1'", 12));
  EXPECT_TRUE(contains(m, "frame 12: object 3: missing attribute 'xc'")) << m;
  m = error_for("<dataset><frame number='5'><objectlist><object><box h='1' w='1' xc='1' yc='1'/></object>"
                "</objectlist></frame></dataset>");
  EXPECT_TRUE(contains(m, "frame 5: <object>: missing attribute 'id'")) << m;
  m = error_for("<dataset><frame><objectlist/></frame></dataset>");
  EXPECT_TRUE(contains(m, "<frame>: missing attribute 'number'")) << m;
  m = error_for("<dataset><frame number='2'><objectlist><object id='1'/></objectlist></frame></dataset>");
  EXPECT_TRUE(contains(m, "frame 2: object 1: missing <box>")) << m;
}

TEST_F(CvmlBroken, NonNumericAttribute) {
  std::string m = error_for(one_box("h='abc' w='1' xc='1' yc='1'", 7));
  EXPECT_TRUE(contains(m, "frame 7: object 3: attribute 'h' is not a finite number: 'abc'")) << m;
  m = error_for(one_box("h='10' w='12px' xc='1' yc='1'"));
  EXPECT_TRUE(contains(m, "attribute 'w' is not a finite number: '12px'")) << m;
  m = error_for(one_box("h='10' w='1' xc='' yc='1'"));
  EXPECT_TRUE(contains(m, "attribute 'xc' is not a finite number: ''")) << m;
  m = error_for(one_box("h='10' w='1' xc='1' yc='inf'"));
  EXPECT_TRUE(contains(m, "attribute 'yc' is not a finite number")) << m;
  m = error_for("<dataset><frame number='1.5'><objectlist/></frame></dataset>");
  EXPECT_TRUE(contains(m, "attribute 'number' is not an integer: '1.5'")) << m;
  m = error_for("<dataset><frame number='0'><objectlist><object id='x1'><box h='1' w='1' xc='1' yc='1'/>"
                "</object></objectlist></frame></dataset>");
  EXPECT_TRUE(contains(m, "frame 0: <object>: attribute 'id' is not a finite number: 'x1'")) << m;
}

TEST_F(CvmlBroken, NegativeSizeOrFrame) {
  std::string m = error_for(one_box("h='-5' w='1' xc='1' yc='1'", 3));
  EXPECT_TRUE(contains(m, path + ": frame 3: object 3: negative box size")) << m;
  m = error_for(one_box("h='5' w='-0.5' xc='1' yc='1'"));
  EXPECT_TRUE(contains(m, "negative box size")) << m;
  m = error_for("<dataset><frame number='-1'><objectlist/></frame></dataset>");
  EXPECT_TRUE(contains(m, "frame -1: negative frame number")) << m;
}

TEST_F(CvmlBroken, EmptyOrFramelessFile) {
  std::string m = error_for("");
  EXPECT_TRUE(contains(m, path + ": empty file")) << m;
  m = error_for("  \n\n");
  EXPECT_TRUE(contains(m, path)) << m;
  m = error_for("<?xml version='1.0'?>\n");
  EXPECT_TRUE(contains(m, path)) << m;
  m = error_for("<dataset/>");
  EXPECT_TRUE(contains(m, path + ": no <frame> elements")) << m;
}

TEST_F(CvmlBroken, MissingFileOrDirectory) {
  const std::string missing = (dir / "missing.xml").string();
  EXPECT_THROW(read_cvml(missing), InputError);
  std::string m = input_error([&] { read_cvml(missing); });
  EXPECT_TRUE(contains(m, missing)) << m;
  std::filesystem::create_directories(dir / "folder.xml");
  m = input_error([&] { read_cvml((dir / "folder.xml").string()); });
  EXPECT_TRUE(contains(m, (dir / "folder.xml").string())) << m;
}

// ---- MOTChallenge -----------------------------------------------------------------------------------

TEST(Mot, GroundTruthFramesAreOneBasedOnDiskAndIgnoredRowsAreFlagged) {
  TempDir dir;
  write_text(dir / "gt.txt",
             "1,1,912,484,97,109,0,7,1.0\n"      // confidence 0 (and class 7): ignored
             "1,2,1338,418,167,379,1,1,1.0\n"    // pedestrian
             "2,2,1340,418,167,379,1,2,0.5\n"    // class 2 (person on vehicle): ignored
             "3,3,100.5,50.25,20,40,0,1,0.5\n"   // pedestrian with confidence 0: ignored
             "5,2,1342,418,167,379,1,1,0.5\n");  // pedestrian
  const GroundTruth gt = read_mot((dir / "gt.txt").string(), true);
  ASSERT_EQ(gt.boxes.size(), 5u);
  EXPECT_EQ(gt.frame_count, 5);
  const std::vector<int> frames = {0, 0, 1, 2, 4}, ids = {1, 2, 2, 3, 2};
  const std::vector<bool> ignored = {true, false, true, true, false};
  for (size_t i = 0; i < gt.boxes.size(); ++i) {
    EXPECT_EQ(gt.boxes[i].frame, frames[i]) << i;
    EXPECT_EQ(gt.boxes[i].id, ids[i]) << i;
    EXPECT_EQ(gt.boxes[i].ignore, ignored[i]) << i;
    EXPECT_DOUBLE_EQ(gt.boxes[i].score, 1.0) << i;  // ground truth carries no score
  }
  EXPECT_EQ(gt.boxes[1].box, Box(1338, 418, 167, 379));
  EXPECT_EQ(gt.boxes[3].box, Box(100.5, 50.25, 20, 40));
  EXPECT_EQ(gt.by_frame().count(3), 0u);
}

TEST(Mot, SixColumnGroundTruthIsNeverIgnored) {
  TempDir dir;
  write_text(dir / "gt.txt", "1,1,10,20,30,40\n2,1,11,21,30,40\n");
  const GroundTruth gt = read_mot((dir / "gt.txt").string(), true);
  ASSERT_EQ(gt.boxes.size(), 2u);
  EXPECT_FALSE(gt.boxes[0].ignore);
  EXPECT_FALSE(gt.boxes[1].ignore);
  EXPECT_EQ(gt.frame_count, 2);
}

TEST(Mot, ResultsKeepConfidenceAsScoreAndAreNeverIgnored) {
  TempDir dir;
  write_text(dir / "res.txt",
             "1,-1,10.50,20.25,30,60,0.875000,-1,-1,-1\n"
             "2,4,11,21,30,60,-0.5,-1,-1,-1\n"
             "2,5,11,21,30,60,0,3,-1,-1\n");  // conf 0 and class 3: a result row, not ignored
  const GroundTruth r = read_mot((dir / "res.txt").string(), false);
  ASSERT_EQ(r.boxes.size(), 3u);
  EXPECT_EQ(r.boxes[0].frame, 0);
  EXPECT_EQ(r.boxes[0].id, -1);
  EXPECT_EQ(r.boxes[0].box, Box(10.5, 20.25, 30, 60));
  EXPECT_DOUBLE_EQ(r.boxes[0].score, 0.875);
  EXPECT_DOUBLE_EQ(r.boxes[1].score, -0.5);
  EXPECT_EQ(r.boxes[1].id, 4);
  EXPECT_EQ(r.boxes[1].frame, 1);
  EXPECT_DOUBLE_EQ(r.boxes[2].score, 0.0);
  for (const auto& b : r.boxes) EXPECT_FALSE(b.ignore);
  EXPECT_EQ(r.frame_count, 2);
}

TEST(Mot, CrlfLineEndingsAndBlankLinesAreAccepted) {
  TempDir dir;
  write_text(dir / "gt.txt",
             "\r\n"
             "1,1,912,484,97,109,1,1,1.0\r\n"
             "   \r\n"
             "\n"
             "2,1,913,485,97,109,1,1,1.0\r\n"
             "\t\r\n");
  const GroundTruth gt = read_mot((dir / "gt.txt").string(), true);
  ASSERT_EQ(gt.boxes.size(), 2u);
  EXPECT_EQ(gt.boxes[1].frame, 1);
  EXPECT_EQ(gt.boxes[1].box, Box(913, 485, 97, 109));
  EXPECT_FALSE(gt.boxes[1].ignore);  // '1\r' read as class 1
  EXPECT_EQ(gt.frame_count, 2);
}

TEST(Mot, ByteOrderMarkIsSkipped) {
  TempDir dir;
  write_text(dir / "gt.txt", "\xEF\xBB\xBF" "1,1,912,484,97,109,1,1,1.0\n");
  const GroundTruth gt = read_mot((dir / "gt.txt").string(), true);
  ASSERT_EQ(gt.boxes.size(), 1u);
  EXPECT_EQ(gt.boxes[0].box, Box(912, 484, 97, 109));
}

TEST(Mot, LastLineWithoutNewlineAndSpaceOrTabSeparatedRows) {
  TempDir dir;
  write_text(dir / "a.txt", "1,1,1,2,3,4\n3,2,5,6,7,8");
  const GroundTruth a = read_mot((dir / "a.txt").string(), false);
  ASSERT_EQ(a.boxes.size(), 2u);
  EXPECT_EQ(a.boxes[1].box, Box(5, 6, 7, 8));
  EXPECT_EQ(a.frame_count, 3);
  write_text(dir / "b.txt", "1 1 1 2 3 4 0.5\n2  2  5  6  7  8  0.25\n");
  const GroundTruth b = read_mot((dir / "b.txt").string(), false);
  ASSERT_EQ(b.boxes.size(), 2u);
  EXPECT_EQ(b.boxes[1].box, Box(5, 6, 7, 8));
  EXPECT_DOUBLE_EQ(b.boxes[1].score, 0.25);
  write_text(dir / "c.txt", "1\t1\t1\t2\t3\t4\t0.5\n");
  const GroundTruth c = read_mot((dir / "c.txt").string(), false);
  ASSERT_EQ(c.boxes.size(), 1u);
  EXPECT_EQ(c.boxes[0].box, Box(1, 2, 3, 4));
}

TEST(Mot, EmptyResultsFileHasNoBoxes) {
  TempDir dir;
  write_text(dir / "res.txt", "");
  const GroundTruth r = read_mot((dir / "res.txt").string(), false);
  EXPECT_TRUE(r.boxes.empty());
  EXPECT_EQ(r.frame_count, 0);
}

class MotBroken : public ::testing::Test {
 protected:
  std::string error_for(const std::string& text) {
    write_text(path, text);
    EXPECT_THROW(read_mot(path, true), InputError);
    return input_error([&] { read_mot(path, true); });
  }
  TempDir dir;
  const std::string path = (dir / "bad.txt").string();
};

TEST_F(MotBroken, TooFewFieldsNamesTheLine) {
  std::string m = error_for("1,1,1,1,5,5\n\n2,1,1,1\n");
  EXPECT_TRUE(contains(m, path + ": line 3: expected at least 6")) << m;
  EXPECT_TRUE(contains(m, "got 4")) << m;
  m = error_for("1,1,1,1,5\n");
  EXPECT_TRUE(contains(m, path + ": line 1")) << m;
  EXPECT_TRUE(contains(m, "got 5")) << m;
}

TEST_F(MotBroken, NonNumberFieldNamesLineAndField) {
  std::string m = error_for("1,1,1,1,5,5\n1,1,x,1,5,5\n");
  EXPECT_TRUE(contains(m, path + ": line 2: field 'x' is not a finite number: 'x'")) << m;
  m = error_for("one,1,1,1,5,5\n");
  EXPECT_TRUE(contains(m, "line 1: field 'frame'")) << m;
  m = error_for("1,1,1,1,5,nan\n");
  EXPECT_TRUE(contains(m, "line 1: field 'h'")) << m;
  m = error_for("1,1,1,1,5,5,high,1,1\n");
  EXPECT_TRUE(contains(m, "line 1: field 'conf'")) << m;
  m = error_for("1,1,1,1,5,5,1,person,1\n");
  EXPECT_TRUE(contains(m, "line 1: field 'class'")) << m;
  m = error_for("1,1,1,,5,5\n");
  EXPECT_TRUE(contains(m, "line 1: field 'y' is not a finite number: ''")) << m;
}

TEST_F(MotBroken, FrameMustBeAPositiveInteger) {
  std::string m = error_for("0,1,1,1,5,5\n");
  EXPECT_TRUE(contains(m, path + ": line 1: field 'frame' must be an integer >= 1")) << m;
  EXPECT_TRUE(contains(m, "1-based")) << m;
  m = error_for("2,1,1,1,5,5\n-3,1,1,1,5,5\n");
  EXPECT_TRUE(contains(m, "line 2: field 'frame'")) << m;
  m = error_for("1.5,1,1,1,5,5\n");
  EXPECT_TRUE(contains(m, "line 1: field 'frame'")) << m;
}

TEST_F(MotBroken, IdMustBeAnInteger) {
  const std::string m = error_for("1,1.5,1,1,5,5\n");
  EXPECT_TRUE(contains(m, path + ": line 1: field 'id'")) << m;
  error_for("1,1e30,1,1,5,5\n");
}

TEST_F(MotBroken, NegativeSizeNamesTheLine) {
  std::string m = error_for("1,1,1,1,5,5\n1,1,1,1,-5,5\n");
  EXPECT_TRUE(contains(m, path + ": line 2: negative box size")) << m;
  m = error_for("1,1,1,1,5,-0.1\n");
  EXPECT_TRUE(contains(m, "line 1: negative box size")) << m;
}

TEST_F(MotBroken, MissingFileOrDirectory) {
  const std::string missing = (dir / "none.txt").string();
  EXPECT_THROW(read_mot(missing, true), InputError);
  EXPECT_TRUE(contains(input_error([&] { read_mot(missing, false); }), missing));
  std::filesystem::create_directories(dir / "folder");
  const std::string folder = (dir / "folder").string();
  EXPECT_TRUE(contains(input_error([&] { read_mot(folder, false); }), folder));
}

// ---- dispatch -----------------------------------------------------------------------------------------

TEST(ReadGroundTruth, DispatchesByExtension) {
  TempDir dir;
  write_text(dir / "gt.xml", kCvml);
  write_text(dir / "GT.XML", kCvml);
  write_text(dir / "gt.txt", "1,1,1,1,5,5,0,1,1\n1,2,1,1,5,5,1,1,1\n");
  write_text(dir / "gt", "2,1,1,1,5,5\n");
  const GroundTruth xml = read_ground_truth((dir / "gt.xml").string());
  EXPECT_EQ(xml.boxes.size(), 3u);
  EXPECT_EQ(xml.frame_count, 2);
  EXPECT_EQ(read_ground_truth((dir / "GT.XML").string()).boxes.size(), 3u);
  const GroundTruth txt = read_ground_truth((dir / "gt.txt").string());
  ASSERT_EQ(txt.boxes.size(), 2u);
  EXPECT_TRUE(txt.boxes[0].ignore);  // read as ground truth
  EXPECT_FALSE(txt.boxes[1].ignore);
  const GroundTruth plain = read_ground_truth((dir / "gt").string());
  ASSERT_EQ(plain.boxes.size(), 1u);
  EXPECT_EQ(plain.boxes[0].frame, 1);
  // A MOT file named .xml is parsed as XML and fails as such.
  write_text(dir / "mot.xml", "1,1,1,1,5,5\n");
  EXPECT_THROW(read_ground_truth((dir / "mot.xml").string()), InputError);
}

TEST(ReadGroundTruth, MissingFileNamesThePath) {
  TempDir dir;
  for (const char* name : {"missing.xml", "missing.txt"}) {
    const std::string path = (dir / name).string();
    EXPECT_THROW(read_ground_truth(path), InputError);
    const std::string m = input_error([&] { read_ground_truth(path); });
    EXPECT_TRUE(contains(m, "ground truth not found: " + path)) << m;
  }
}

TEST(ReadGroundTruth, EmptyMotGroundTruthIsAnInputError) {
  TempDir dir;
  for (const char* text : {"", "\n  \n"}) {
    write_text(dir / "gt.txt", text);
    EXPECT_EQ(input_error([&] { read_ground_truth((dir / "gt.txt").string()); }),
              (dir / "gt.txt").string() + ": no ground-truth rows (empty file)");
  }
}

}  // namespace
}  // namespace bodyrec
