// Penn-Fudan ground truth: tight boxes from instance masks, the split, and loading a drawn Penn-Fudan-like
// folder with its broken variants.
#include "bodyrec/io/pennfudan.h"

#include <filesystem>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "synthetic_silhouette.h"
#include "test_support.h"

namespace fs = std::filesystem;

namespace bodyrec {
namespace {

using testing::contains;
using testing::input_error;

TEST(InstanceMaskBoxes, TightBoxOfEachValueInOrder) {
  cv::Mat mask = cv::Mat::zeros(100, 80, CV_8U);
  mask(cv::Rect(10, 20, 5, 30)).setTo(1);
  mask.at<uchar>(60, 70) = 1;           // a stray pixel of person 1 widens its box
  mask(cv::Rect(40, 5, 12, 40)).setTo(2);
  mask.at<uchar>(99, 0) = 4;            // person 4: one pixel; value 3 has no pixels
  const std::vector<Box> boxes = instance_mask_boxes(mask);
  ASSERT_EQ(boxes.size(), 3u);
  EXPECT_EQ(boxes[0], Box(10, 20, 61, 41));  // x 10..70, y 20..60 inclusive
  EXPECT_EQ(boxes[1], Box(40, 5, 12, 40));
  EXPECT_EQ(boxes[2], Box(0, 99, 1, 1));
}

TEST(InstanceMaskBoxes, EmptyMaskHasNobody) {
  EXPECT_TRUE(instance_mask_boxes(cv::Mat::zeros(10, 10, CV_8U)).empty());
}

TEST(InstanceMaskBoxes, RefusesMasksThatAreNotEightBitSingleChannel) {
  EXPECT_TRUE(contains(input_error([] { instance_mask_boxes(cv::Mat::zeros(10, 10, CV_8UC3), "m.png"); }), "m.png"));
  EXPECT_TRUE(contains(input_error([] { instance_mask_boxes(cv::Mat::zeros(10, 10, CV_16U), "m16.png"); }), "m16.png"));
}

TEST(PennFudanSplit, EveryFourthImageFromTheFourthIsTest) {
  EXPECT_FALSE(pennfudan_is_test(0));
  EXPECT_FALSE(pennfudan_is_test(2));
  EXPECT_TRUE(pennfudan_is_test(3));
  EXPECT_TRUE(pennfudan_is_test(7));
  EXPECT_TRUE(in_pennfudan_split(3, PennFudanSplit::kTest));
  EXPECT_FALSE(in_pennfudan_split(3, PennFudanSplit::kTrain));
  EXPECT_TRUE(in_pennfudan_split(4, PennFudanSplit::kTrain));
  EXPECT_TRUE(in_pennfudan_split(3, PennFudanSplit::kAll));
}

TEST(LoadPennFudan, SplitsAndReadsBoxesFromTheMasks) {
  testing::TempDir dir;
  testing::make_pennfudan_like(dir / "pf");
  const auto test = load_pennfudan((dir / "pf").string(), PennFudanSplit::kTest);
  ASSERT_EQ(test.size(), 2u);
  EXPECT_EQ(fs::path(test[0].image_path).filename(), "P03.png");
  EXPECT_EQ(fs::path(test[1].image_path).filename(), "P07.png");
  EXPECT_EQ(fs::path(test[1].mask_path).filename(), "P07_mask.png");
  EXPECT_EQ(test[0].size, cv::Size(240, 200));
  const cv::Mat mask = cv::imread(test[0].mask_path, cv::IMREAD_GRAYSCALE);
  ASSERT_EQ(test[0].people.size(), 1u);
  EXPECT_EQ(test[0].people[0], Box(cv::boundingRect(mask == 1)));

  const auto train = load_pennfudan((dir / "pf").string(), PennFudanSplit::kTrain);
  ASSERT_EQ(train.size(), 6u);
  size_t people = 0;
  for (const auto& image : train) people += image.people.size();
  EXPECT_EQ(people, 9u);  // P01, P02 and P05 have two people
  EXPECT_EQ(load_pennfudan((dir / "pf").string(), PennFudanSplit::kAll).size(), 8u);
}

TEST(LoadPennFudan, BrokenFoldersNameTheFileAtFault) {
  testing::TempDir dir;
  EXPECT_TRUE(contains(input_error([&] { load_pennfudan((dir / "none").string(), PennFudanSplit::kTest); }),
                       "PNGImages"));
  const fs::path pf = dir / "pf";
  testing::make_pennfudan_like(pf);

  fs::rename(pf / "PedMasks" / "P03_mask.png", dir / "kept.png");  // an image without its mask
  EXPECT_TRUE(contains(input_error([&] { load_pennfudan(pf.string(), PennFudanSplit::kTest); }), "P03_mask.png"));
  // A train image's missing mask does not stop the test split from loading.
  fs::rename(dir / "kept.png", pf / "PedMasks" / "P03_mask.png");
  fs::rename(pf / "PedMasks" / "P00_mask.png", dir / "kept.png");
  EXPECT_EQ(load_pennfudan(pf.string(), PennFudanSplit::kTest).size(), 2u);
  EXPECT_TRUE(contains(input_error([&] { load_pennfudan(pf.string(), PennFudanSplit::kTrain); }), "P00_mask.png"));
  fs::rename(dir / "kept.png", pf / "PedMasks" / "P00_mask.png");

  fs::copy_file(pf / "PedMasks" / "P00_mask.png", pf / "PedMasks" / "Q09_mask.png");  // a mask without its image
  EXPECT_TRUE(contains(input_error([&] { load_pennfudan(pf.string(), PennFudanSplit::kTest); }), "Q09_mask.png"));
  fs::remove(pf / "PedMasks" / "Q09_mask.png");

  testing::write_text(pf / "PedMasks" / "P07_mask.png", "not a png");  // an unreadable mask
  EXPECT_TRUE(contains(input_error([&] { load_pennfudan(pf.string(), PennFudanSplit::kTest); }), "P07_mask.png"));
  cv::imwrite((pf / "PedMasks" / "P07_mask.png").string(), cv::Mat(200, 240, CV_8UC3, cv::Scalar(1, 1, 1)));
  EXPECT_TRUE(contains(input_error([&] { load_pennfudan(pf.string(), PennFudanSplit::kTest); }), "P07_mask.png"));

  fs::remove_all(pf / "PedMasks");
  EXPECT_TRUE(contains(input_error([&] { load_pennfudan(pf.string(), PennFudanSplit::kTest); }), "PedMasks"));
  for (const auto& entry : fs::directory_iterator(pf / "PNGImages")) fs::remove(entry.path());
  EXPECT_TRUE(contains(input_error([&] { load_pennfudan(pf.string(), PennFudanSplit::kTest); }), "no .png images"));
}

}  // namespace
}  // namespace bodyrec
