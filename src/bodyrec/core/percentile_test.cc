#include "bodyrec/core/percentile.h"

#include <gtest/gtest.h>

namespace bodyrec {
namespace {

TEST(Percentile, NearestRank) {
  std::vector<double> v;
  for (int i = 100; i >= 1; --i) v.push_back(i);  // unsorted on purpose
  EXPECT_EQ(percentile(v, 95), 95);
  EXPECT_EQ(percentile(v, 50), 50);
  EXPECT_EQ(percentile(v, 100), 100);
  EXPECT_EQ(percentile(v, 0), 1);
  EXPECT_EQ(percentile({7, 3}, 50), 3);
  EXPECT_EQ(percentile({7, 3}, 51), 7);
  EXPECT_EQ(percentile({}, 95), 0);
}

}  // namespace
}  // namespace bodyrec
