#include "bodyrec/io/json_numbers.h"

#include <cmath>
#include <limits>
#include <sstream>

#include <gtest/gtest.h>

#include "bodyrec/io/sinks.h"
#include "test_support.h"

namespace bodyrec {
namespace {

using nlohmann::json;

TEST(JsonNumbers, DoublesKeepSixSignificantDigits) {
  EXPECT_EQ(json(0.07857 * 1.0000000000000002).dump(), "0.07857000000000001");  // what a plain dump writes
  EXPECT_EQ(json_text(0.07857 * 1.0000000000000002), "0.07857");
  EXPECT_EQ(json(3 * 0.1).dump(), "0.30000000000000004");
  EXPECT_EQ(json_text(3 * 0.1), "0.3");
  EXPECT_EQ(json_text(3.9680361234), "3.96804");
  EXPECT_EQ(json_text(1.0 / 3), "0.333333");
  EXPECT_EQ(json_text(-2.0 / 3e-9), "-666666666.667");  // the integer part and three decimals are kept
  EXPECT_EQ(json_text(1733312345.25), "1733312345.25");    // a Unix time keeps its milliseconds
  EXPECT_EQ(json_text(12345.6789), "12345.7");
  EXPECT_EQ(json_text(123456.789), "123456.789");
  EXPECT_EQ(json_text(1.23456789e-7), "1.23457e-07");
  EXPECT_EQ(json_text(504.41), "504.41");  // already short: unchanged
  EXPECT_EQ(json_text(0.0), "0.0");
  EXPECT_EQ(json_text(1e300), "1e+300");
  EXPECT_EQ(round_significant(std::numeric_limits<double>::infinity()), std::numeric_limits<double>::infinity());
  EXPECT_TRUE(std::isnan(round_significant(std::nan(""))));
  EXPECT_EQ(round_significant(2.0 / 3, 2), 0.67);
}

TEST(JsonNumbers, EveryDoubleAtAnyDepthIsRoundedAndIntegersAreNot) {
  const json row = {{"frame", 123456789},
                    {"time", 4.966666666666667},
                    {"detections", {{{"box", {504.4100000001, 158.99, 24.38, 73.13}}, {"score", 3.9680361234}}}},
                    {"name", "0.07856999999999999"},
                    {"ok", true},
                    {"none", nullptr}};
  EXPECT_EQ(json_text(row),
            R"({"detections":[{"box":[504.41,158.99,24.38,73.13],"score":3.96804}],"frame":123456789,"name":)"
            R"("0.07856999999999999","none":null,"ok":true,"time":4.96667})");
}

TEST(JsonNumbers, JsonlWriterRoundsItsLines) {
  testing::TempDir dir;
  const std::string path = (dir / "out.jsonl").string();
  {
    JsonlWriter out(path);
    out.write({{"frame", 0}, {"x", 0.1 * 0.7857}});
  }
  EXPECT_EQ(testing::read_text(path), "{\"frame\":0,\"x\":0.07857}\n");
}

}  // namespace
// nlohmann's dump() writes some doubles with 16-17 digits (8.735290000000001); json_text writes the
// shortest text that reads back, in nlohmann's layout.
TEST(JsonNumbers, JsonTextWritesTheShortestNumbers) {
  EXPECT_EQ(nlohmann::json(8.73529).dump(), "8.735290000000001");  // why json_text has its own writer
  EXPECT_EQ(json_text(nlohmann::json{{"ms", 8.73529}, {"q", 0.874778}}), "{\"ms\":8.73529,\"q\":0.874778}");
  EXPECT_EQ(json_text(nlohmann::json::array({100.0, 1e-05, 1e20, -2.5, 0.0, 1733312345.25, 3})),
            "[100.0,1e-05,1e+20,-2.5,0.0,1733312345.25,3]");
  EXPECT_EQ(json_text(nlohmann::json{{"s", "a\"b"}, {"n", nullptr}, {"t", true}, {"inf", HUGE_VAL}}),
            "{\"inf\":null,\"n\":null,\"s\":\"a\\\"b\",\"t\":true}");
}

}  // namespace bodyrec
