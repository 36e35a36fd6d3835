#include "bodyrec/core/view.h"

#include <algorithm>

#include <gtest/gtest.h>

namespace bodyrec {
namespace {

TEST(View, NamesRoundTripInThesisOrder) {
  EXPECT_STREQ(view_name(View::F), "F");
  EXPECT_STREQ(view_name(View::BL), "BL");
  EXPECT_EQ(static_cast<int>(View::SR), 3);
  for (View v : kAllViews) EXPECT_EQ(parse_view(view_name(v)), v);
  EXPECT_FALSE(parse_view("f").has_value());
  EXPECT_FALSE(parse_view("").has_value());
}

TEST(View, ComplementaryPairsAreTheThesisOnesBothWays) {
  EXPECT_EQ(complementary_views(View::F), std::vector<View>({View::FR}));
  EXPECT_EQ(complementary_views(View::FR), std::vector<View>({View::F, View::FL}));
  EXPECT_EQ(complementary_views(View::BR), std::vector<View>({View::B, View::BL}));
  EXPECT_EQ(complementary_views(View::SL), std::vector<View>({View::SR}));
  // Symmetric: if b complements a then a complements b.
  for (View a : kAllViews)
    for (View b : complementary_views(a)) {
      const auto back = complementary_views(b);
      EXPECT_NE(std::find(back.begin(), back.end(), a), back.end()) << view_name(a) << "-" << view_name(b);
    }
}

}  // namespace
}  // namespace bodyrec
