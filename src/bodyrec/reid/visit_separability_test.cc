#include "bodyrec/reid/visit_separability.h"

#include <gtest/gtest.h>

namespace bodyrec {
namespace {

// The stripes descriptor of a whole-body crop (60x180) with a shirt over trousers.
std::vector<float> dressed(const AppearanceMatcher& m, const cv::Scalar& shirt, const cv::Scalar& trousers) {
  cv::Mat img(180, 60, CV_8UC3, trousers);
  img(cv::Rect(0, 0, 60, 90)).setTo(shirt);
  return m.describe(PersonImage{img, cv::Mat()});
}

const cv::Scalar kRed(40, 40, 200), kBlue(200, 60, 30), kGreen(40, 180, 40), kYellow(40, 220, 230);

TEST(VisitSeparability, PeopleDressedTheSameOnEveryVisitAreTheirOwnNeighbours) {
  const auto m = make_matcher("stripes");
  VisitSeparability sep(*m);
  sep.add(0, 10, dressed(*m, kRed, kBlue));
  sep.add(0, 10, dressed(*m, kRed, kBlue));
  sep.add(1, 11, dressed(*m, kGreen, kYellow));
  sep.add(0, 12, dressed(*m, kRed, kBlue));
  sep.add(1, 13, dressed(*m, kGreen, kYellow));
  sep.add(2, 14, dressed(*m, kYellow, kGreen));  // seen once: a neighbour, never a probe
  const VisitSeparability::Score s = sep.score();
  EXPECT_EQ(s.probes, 5);
  EXPECT_DOUBLE_EQ(s.nn_accuracy, 1.0);
  EXPECT_DOUBLE_EQ(s.above_threshold, 1.0);
}

TEST(VisitSeparability, SomeoneWhoChangedClothesMatchesWhoeverLooksLikeThem) {
  const auto m = make_matcher("stripes");
  VisitSeparability sep(*m);
  sep.add(0, 1, dressed(*m, kRed, kBlue));
  sep.add(0, 2, dressed(*m, kGreen, kYellow));
  sep.add(1, 3, dressed(*m, kRed, kYellow));  // shares the shirt of visit 1 and the trousers of visit 2
  const VisitSeparability::Score s = sep.score();
  EXPECT_EQ(s.probes, 2);
  EXPECT_DOUBLE_EQ(s.nn_accuracy, 0.0);
  EXPECT_DOUBLE_EQ(s.above_threshold, 0.0);
}

TEST(VisitSeparability, NoPersonSeenTwiceGivesNoProbes) {
  const auto m = make_matcher("stripes");
  VisitSeparability sep(*m);
  EXPECT_EQ(sep.score().probes, 0);
  sep.add(0, 1, dressed(*m, kRed, kBlue));
  sep.add(1, 2, dressed(*m, kRed, kBlue));
  const VisitSeparability::Score s = sep.score();
  EXPECT_EQ(s.probes, 0);
  EXPECT_DOUBLE_EQ(s.nn_accuracy, 0.0);
}

}  // namespace
}  // namespace bodyrec
