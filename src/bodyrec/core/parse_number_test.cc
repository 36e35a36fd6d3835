#include "bodyrec/core/parse_number.h"

#include <cmath>

#include <gtest/gtest.h>

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace {

TEST(ParseNumber, WholeTokensOnly) {
  EXPECT_EQ(parse_double("1.5"), 1.5);
  EXPECT_EQ(parse_double(" -2e3\t"), -2000.0);
  EXPECT_EQ(parse_double("7.8000000e+02"), 780.0);
  EXPECT_FALSE(parse_double(""));
  EXPECT_FALSE(parse_double("  "));
  EXPECT_FALSE(parse_double("1.5x"));
  EXPECT_FALSE(parse_double("1,5"));
  EXPECT_FALSE(parse_double("abc"));
  EXPECT_TRUE(std::isnan(*parse_double("nan")));
  EXPECT_TRUE(std::isinf(*parse_double("1e999")));
}

TEST(ParseNumber, Integers) {
  EXPECT_EQ(parse_integer("42"), 42);
  EXPECT_EQ(parse_integer(" -7 "), -7);
  EXPECT_EQ(parse_integer("72057594037927936"), 72057594037927936LL);
  EXPECT_FALSE(parse_integer("1.0"));
  EXPECT_FALSE(parse_integer("99999999999999999999"));
  EXPECT_FALSE(parse_integer(""));
}

TEST(ParseNumber, FiniteFieldErrorNamesWhereAndField) {
  EXPECT_EQ(parse_finite_field("3.25", "f.txt:2", "x"), 3.25);
  try {
    parse_finite_field("inf", "f.txt:2", "x");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "f.txt:2: field 'x' is not a finite number: 'inf'");
  }
}

}  // namespace
}  // namespace bodyrec
