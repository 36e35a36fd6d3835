// dlib imglab XML: round trip, landmark ordering, image paths, and broken files. Every broken file must give
// an InputError whose message names the file and the image, box or part at fault.
#include "bodyrec/io/imglab_xml.h"

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

ImglabDataset sample_dataset() {
  ImglabDataset d;
  d.name = "bodies & shapes";
  d.comment = "made by a test <with> markup";
  ImglabImage a{"images/a.png", {}};
  ImglabBox body;
  body.box = Box(10, 20, 30, 60);
  body.label = "body_detected";
  body.parts = {{"01", {12, 25}}, {"00", {11, 21}}, {"03", {14, 40}}, {"02", {13, 30}}};
  a.boxes.push_back(body);
  ImglabBox ignored;
  ignored.box = Box(100, 100, 5, 5);
  ignored.ignore = true;
  a.boxes.push_back(ignored);
  d.images.push_back(a);
  d.images.push_back(ImglabImage{"/data/b.jpg", {}});  // an image without boxes
  ImglabImage c{"c.png", {}};
  ImglabBox other;
  other.box = Box(0, 0, 640, 480);
  other.label = "person";
  c.boxes.push_back(other);
  d.images.push_back(c);
  return d;
}

TEST(Imglab, RoundTripKeepsBoxesLabelsIgnoreAndParts) {
  TempDir dir;
  const std::string path = (dir / "set.xml").string();
  write_imglab(sample_dataset(), path);

  const ImglabDataset back = read_imglab(path);
  EXPECT_EQ(back.name, "bodies & shapes");
  EXPECT_EQ(back.comment, "made by a test <with> markup");
  ASSERT_EQ(back.images.size(), 3u);
  EXPECT_EQ(back.images[0].file, "images/a.png");
  EXPECT_EQ(back.images[1].file, "/data/b.jpg");
  EXPECT_EQ(back.images[2].file, "c.png");
  ASSERT_EQ(back.images[0].boxes.size(), 2u);
  EXPECT_TRUE(back.images[1].boxes.empty());
  ASSERT_EQ(back.images[2].boxes.size(), 1u);

  const ImglabBox& body = back.images[0].boxes[0];
  EXPECT_EQ(body.box, Box(10, 20, 30, 60));
  EXPECT_EQ(body.label, "body_detected");
  EXPECT_FALSE(body.ignore);
  ASSERT_EQ(body.parts.size(), 4u);
  EXPECT_EQ(body.parts[0].name, "01");  // file order is kept
  EXPECT_EQ(body.parts[0].point, cv::Point2d(12, 25));

  const ImglabBox& ignored = back.images[0].boxes[1];
  EXPECT_EQ(ignored.box, Box(100, 100, 5, 5));
  EXPECT_TRUE(ignored.ignore);
  EXPECT_TRUE(ignored.label.empty());
  EXPECT_TRUE(ignored.parts.empty());

  EXPECT_EQ(back.images[2].boxes[0].box, Box(0, 0, 640, 480));
  EXPECT_EQ(back.images[2].boxes[0].label, "person");

  // Writing what was read gives the same file.
  const std::string again = (dir / "again.xml").string();
  write_imglab(back, again);
  EXPECT_EQ(testing::read_text(again), testing::read_text(path));
}

TEST(Imglab, WritesIntegerCoordinatesTheWayDlibDoes) {
  TempDir dir;
  ImglabDataset d;
  ImglabBox b;
  b.box = Box(10.4, 19.6, 30.2, 59.5);
  b.parts = {{"00", {11.4, 20.6}}};
  d.images.push_back(ImglabImage{"a.png", {b}});
  const std::string path = (dir / "set.xml").string();
  write_imglab(d, path);
  const std::string text = testing::read_text(path);
  EXPECT_TRUE(contains(text, "<box top=\"20\" left=\"10\" width=\"30\" height=\"60\">")) << text;
  EXPECT_TRUE(contains(text, "<part name=\"00\" x=\"11\" y=\"21\"")) << text;
  const ImglabDataset back = read_imglab(path);
  EXPECT_EQ(back.images[0].boxes[0].box, Box(10, 20, 30, 60));
}

TEST(Imglab, ReadsDlibStyleFileWithDeclarationAndStylesheet) {
  TempDir dir;
  write_text(dir / "dlib.xml",
             "<?xml version='1.0' encoding='ISO-8859-1'?>\n"
             "<?xml-stylesheet type='text/xsl' href='image_metadata_stylesheet.xsl'?>\n"
             "<dataset>\n<name>imglab dataset</name>\n<comment>Created by imglab tool.</comment>\n<images>\n"
             "  <image file='x/Snapshot_1.JPG'>\n"
             "    <box top='51' left='187' width='186' height='394'>\n"
             "      <label>body_detected</label>\n"
             "    </box>\n"
             "    <box top='1' left='2' width='3' height='4' ignore='1'/>\n"
             "  </image>\n</images>\n</dataset>\n");
  const ImglabDataset d = read_imglab((dir / "dlib.xml").string());
  EXPECT_EQ(d.name, "imglab dataset");
  EXPECT_EQ(d.comment, "Created by imglab tool.");
  ASSERT_EQ(d.images.size(), 1u);
  ASSERT_EQ(d.images[0].boxes.size(), 2u);
  EXPECT_EQ(d.images[0].boxes[0].box, Box(187, 51, 186, 394));
  EXPECT_EQ(d.images[0].boxes[0].label, "body_detected");
  EXPECT_FALSE(d.images[0].boxes[0].ignore);
  EXPECT_TRUE(d.images[0].boxes[1].ignore);
}

TEST(Imglab, WriteToMissingFolderIsProcessingError) {
  TempDir dir;
  EXPECT_THROW(write_imglab(sample_dataset(), (dir / "no" / "such" / "folder" / "x.xml").string()),
               ProcessingError);
}

// ---- ordered_parts ----------------------------------------------------------------------------------

TEST(OrderedParts, SortsNumericNames) {
  ImglabBox box;
  box.parts = {{"02", {13, 30}}, {"00", {11, 21}}, {"03", {14, 40}}, {"01", {12, 25}}};
  const auto points = ordered_parts(box, "box");
  ASSERT_EQ(points.size(), 4u);
  EXPECT_EQ(points[0], cv::Point2d(11, 21));
  EXPECT_EQ(points[1], cv::Point2d(12, 25));
  EXPECT_EQ(points[2], cv::Point2d(13, 30));
  EXPECT_EQ(points[3], cv::Point2d(14, 40));
  // Numbers, not strings: "10" comes after "9", and "00"/"0" are the same index.
  box.parts.clear();
  for (int i = 11; i >= 0; --i) box.parts.push_back({std::to_string(i), {double(i), 0}});
  const auto twelve = ordered_parts(box, "box");
  ASSERT_EQ(twelve.size(), 12u);
  for (int i = 0; i < 12; ++i) EXPECT_EQ(twelve[i].x, i);
  EXPECT_TRUE(ordered_parts(ImglabBox{}, "box").empty());
}

TEST(OrderedParts, BadNamesAreInputErrorsNamingTheBox) {
  ImglabBox box;
  box.parts = {{"00", {0, 0}}, {"02", {1, 1}}};
  EXPECT_THROW(ordered_parts(box, "img.png box 0"), InputError);
  std::string m = input_error([&] { ordered_parts(box, "img.png box 0"); });
  EXPECT_TRUE(contains(m, "img.png box 0: landmark 1 is missing")) << m;
  box.parts = {{"01", {0, 0}}};
  m = input_error([&] { ordered_parts(box, "b1"); });
  EXPECT_TRUE(contains(m, "b1: landmark 0 is missing")) << m;
  box.parts = {{"00", {0, 0}}, {"01", {0, 0}}, {"0", {1, 1}}};
  m = input_error([&] { ordered_parts(box, "b2"); });
  EXPECT_TRUE(contains(m, "b2: part 0 appears twice")) << m;
  box.parts = {{"00", {0, 0}}, {"head", {0, 0}}};
  m = input_error([&] { ordered_parts(box, "b3"); });
  EXPECT_TRUE(contains(m, "b3: part name 'head' is not a landmark number")) << m;
  for (const char* name : {"", "1a", "-1", " 1", "+1", "1.0"}) {
    box.parts = {{"00", {0, 0}}, {name, {0, 0}}};
    m = input_error([&] { ordered_parts(box, "b4"); });
    EXPECT_TRUE(contains(m, "b4: part name '" + std::string(name) + "' is not a landmark number"))
        << "name '" << name << "': " << m;
  }
}

// ---- resolve_image_path -----------------------------------------------------------------------------

TEST(ResolveImagePath, RelativeToTheXmlFolderAbsoluteKept) {
  EXPECT_EQ(resolve_image_path("/data/sets/train.xml", "images/a.png"), "/data/sets/images/a.png");
  EXPECT_EQ(resolve_image_path("/data/sets/train.xml", "../other/b.png"), "/data/other/b.png");
  EXPECT_EQ(resolve_image_path("/data/sets/train.xml", "./c.png"), "/data/sets/c.png");
  EXPECT_EQ(resolve_image_path("/data/sets/train.xml", "/abs/b.png"), "/abs/b.png");
  EXPECT_EQ(resolve_image_path("sets/train.xml", "a.png"), "sets/a.png");
  EXPECT_EQ(resolve_image_path("train.xml", "a.png"), "a.png");
}

// ---- broken files -----------------------------------------------------------------------------------

class ImglabBroken : public ::testing::Test {
 protected:
  std::string error_for(const std::string& text) {
    write_text(path, text);
    EXPECT_THROW(read_imglab(path), InputError);
    return input_error([&] { read_imglab(path); });
  }
  // A dataset whose single image holds `inside`.
  static std::string image(const std::string& inside, const std::string& file = "a.png") {
    return "<dataset><images><image file='" + file + "'>" + inside + "</image></images></dataset>";
  }
  TempDir dir;
  const std::string path = (dir / "bad.xml").string();
};

TEST_F(ImglabBroken, TruncatedXmlNamesFileAndLine) {
  const std::string m = error_for("<dataset>\n<images>\n<image file='a.png'>\n<box top='1' left='2' width='3'");
  EXPECT_TRUE(contains(m, path + ": line 4: malformed XML")) << m;
}

TEST_F(ImglabBroken, WrongRootEmptyOrMissingFile) {
  std::string m = error_for("<images/>");
  EXPECT_TRUE(contains(m, path + ": not an imglab dataset")) << m;
  m = error_for("");
  EXPECT_TRUE(contains(m, path + ": empty file")) << m;
  const std::string missing = (dir / "missing.xml").string();
  EXPECT_THROW(read_imglab(missing), InputError);
  m = input_error([&] { read_imglab(missing); });
  EXPECT_TRUE(contains(m, missing)) << m;
}

TEST_F(ImglabBroken, ImageWithoutFile) {
  const std::string m = error_for(
      "<dataset><images><image file='ok.png'/><image><box top='1' left='2' width='3' height='4'/></image>"
      "</images></dataset>");
  EXPECT_TRUE(contains(m, path + ": image 1: missing attribute 'file'")) << m;
}

TEST_F(ImglabBroken, BoxWithoutCoordinate) {
  std::string m = error_for(image("<box top='1' width='3' height='4'/>"));
  EXPECT_TRUE(contains(m, path + ": image a.png: box 0: missing attribute 'left'")) << m;
  m = error_for(image("<box top='1' left='1' width='3' height='4'/><box left='1' width='3' height='4'/>"));
  EXPECT_TRUE(contains(m, "image a.png: box 1: missing attribute 'top'")) << m;
  m = error_for(image("<box top='1' left='1' width='3'/>"));
  EXPECT_TRUE(contains(m, "box 0: missing attribute 'height'")) << m;
  m = error_for(image("<box top='1' left='1' width='wide' height='4'/>"));
  EXPECT_TRUE(contains(m, "box 0: attribute 'width' is not a finite number: 'wide'")) << m;
}

TEST_F(ImglabBroken, NegativeSize) {
  std::string m = error_for(image("<box top='1' left='1' width='-3' height='4'/>", "neg.png"));
  EXPECT_TRUE(contains(m, path + ": image neg.png: box 0: negative width or height")) << m;
  m = error_for(image("<box top='1' left='1' width='3' height='-4'/>"));
  EXPECT_TRUE(contains(m, "negative width or height")) << m;
}

TEST_F(ImglabBroken, PartWithoutCoordinateOrName) {
  std::string m = error_for(image("<box top='1' left='1' width='3' height='4'><part name='00' y='3'/></box>"));
  EXPECT_TRUE(contains(m, path + ": image a.png: box 0: part 00: missing attribute 'x'")) << m;
  m = error_for(image("<box top='1' left='1' width='3' height='4'><part name='07' x='3'/></box>"));
  EXPECT_TRUE(contains(m, "box 0: part 07: missing attribute 'y'")) << m;
  m = error_for(image("<box top='1' left='1' width='3' height='4'><part name='07' x='3' y='?'/></box>"));
  EXPECT_TRUE(contains(m, "part 07: attribute 'y' is not a finite number: '?'")) << m;
  m = error_for(image("<box top='1' left='1' width='3' height='4'><part x='3' y='4'/></box>"));
  EXPECT_TRUE(contains(m, "box 0: <part> without attribute 'name'")) << m;
}

}  // namespace
}  // namespace bodyrec
