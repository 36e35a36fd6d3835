#include "bodyrec/report/svg.h"

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "bodyrec/report/html.h"

namespace bodyrec::report {
namespace {

int count(const std::string& text, const std::string& part) {
  int n = 0;
  for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + part.size())) ++n;
  return n;
}

std::vector<unsigned char> unbase64(const std::string& text) {
  const std::string k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::vector<unsigned char> out;
  unsigned buffer = 0;
  int bits = 0;
  for (char c : text) {
    const size_t v = k.find(c);
    if (v == std::string::npos) break;
    buffer = (buffer << 6) | static_cast<unsigned>(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<unsigned char>((buffer >> bits) & 0xFF));
    }
  }
  return out;
}

TEST(Html, EscapesMarkupCharacters) {
  EXPECT_EQ(html_escape("<script>alert('x')</script> & \"q\""),
            "&lt;script&gt;alert(&#39;x&#39;)&lt;/script&gt; &amp; &quot;q&quot;");
  EXPECT_EQ(html_escape("plain"), "plain");
}

TEST(Html, Base64MatchesRfc4648) {
  auto b = [](const std::string& s) { return base64(std::vector<unsigned char>(s.begin(), s.end())); };
  EXPECT_EQ(b(""), "");
  EXPECT_EQ(b("M"), "TQ==");
  EXPECT_EQ(b("Ma"), "TWE=");
  EXPECT_EQ(b("Man"), "TWFu");
  EXPECT_EQ(b("foobar"), "Zm9vYmFy");
}

TEST(Html, JpegDataUriIsDownscaledTo640Wide) {
  cv::Mat image(720, 1280, CV_8UC3, cv::Scalar(40, 120, 200));
  const std::string uri = jpeg_data_uri(image);
  const std::string prefix = "data:image/jpeg;base64,";
  ASSERT_EQ(uri.rfind(prefix, 0), 0u);
  const cv::Mat decoded = cv::imdecode(unbase64(uri.substr(prefix.size())), cv::IMREAD_COLOR);
  ASSERT_FALSE(decoded.empty());
  EXPECT_EQ(decoded.cols, 640);
  EXPECT_EQ(decoded.rows, 360);
  const cv::Mat small(100, 50, CV_8UC3, cv::Scalar::all(0));
  EXPECT_EQ(cv::imdecode(unbase64(jpeg_data_uri(small).substr(prefix.size())), cv::IMREAD_COLOR).cols, 50);
}

TEST(Html, TableEscapesCellsAndLegendEscapesLabels) {
  const std::string t = html_table({"a", "b"}, {{"<b>", "1"}, {"x", "2"}});
  EXPECT_EQ(count(t, "<tr>"), 3);
  EXPECT_NE(t.find("&lt;b&gt;"), std::string::npos);
  EXPECT_EQ(t.find("<b>"), std::string::npos);
  EXPECT_NE(html_legend({{"#fff", "<i>"}}).find("&lt;i&gt;"), std::string::npos);
}

TEST(Svg, NiceTicksUseRoundSteps) {
  EXPECT_EQ(nice_ticks(0, 10, 5), (std::vector<double>{0, 2, 4, 6, 8, 10}));
  const auto fractions = nice_ticks(0, 1, 5);
  ASSERT_EQ(fractions.size(), 6u);
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(fractions[i], 0.2 * i, 1e-9);
  EXPECT_EQ(nice_ticks(3, 3, 5), (std::vector<double>{3}));
  EXPECT_EQ(nice_ticks(0, 795, 8).back(), 700);
}

TEST(Svg, AxesMapDataToTheInnerRectangle) {
  PlotFrame f;  // 760 x 260, margins l56 r16 t14 b44
  const Axes a(f, 0, 100, 0, 10);
  EXPECT_DOUBLE_EQ(a.px(0), 56);
  EXPECT_DOUBLE_EQ(a.px(100), 744);
  EXPECT_DOUBLE_EQ(a.py(0), 216);
  EXPECT_DOUBLE_EQ(a.py(10), 14);
}

TEST(Svg, LinePlotDrawsOnePolylinePerSeriesAndMarkers) {
  Series s{"cmc", "#00f", {}, {}, false, true};
  for (int r = 1; r <= 20; ++r) {
    s.x.push_back(r);
    s.y.push_back(r / 20.0);
  }
  Series t{"other <x>", "#f00", {1, 2}, {0.5, 0.6}, true, false};
  const std::string svg = line_plot({s, t}, PlotFrame{}, 0.0, 1.0);
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_EQ(count(svg, "<polyline"), 2);
  EXPECT_EQ(count(svg, "class=\"point\""), 20);
  EXPECT_NE(svg.find("other &lt;x&gt;"), std::string::npos);
}

TEST(Svg, BarChartHistogramAndRoseCountTheirShapes) {
  EXPECT_EQ(count(bar_chart({{"a", "#f00", 0.5, ""}, {"b", "#0f0", 0.7, ""}, {"c", "#00f", 0.2, ""}}, PlotFrame{}),
                  "class=\"bar\""),
            3);
  std::vector<int> counts;
  const std::string h = histogram({0, 0, 0.1, 0.5, 0.95, 1.0}, 4, PlotFrame{}, "#0aa", &counts);
  EXPECT_EQ(counts, (std::vector<int>{3, 0, 1, 2}));
  EXPECT_EQ(count(h, "class=\"bin\""), 4);
  EXPECT_EQ(count(polar_rose({1, 0, 2, 0, 0, 0, 0, 0}, "#00f"), "class=\"petal\""), 2);
  EXPECT_EQ(count(polar_rose({0, 0, 0, 0}, "#00f"), "class=\"petal\""), 0);
}

TEST(Svg, StripTimelineHasOneRowPerEntryAndEscapesLabels) {
  std::vector<StripRow> rows(3);
  rows[0] = {"<script>", {{0, 10, "#00f", "a"}, {12, 20, "#f00", "b"}}};
  rows[1] = {"#2", {{5, 6, "#0f0", "c"}}};
  rows[2] = {"#3", {}};
  const std::string svg = strip_timeline(rows, 0, 20, "frame");
  EXPECT_EQ(count(svg, "class=\"tl-row\""), 3);
  EXPECT_EQ(count(svg, "<rect"), 3);
  EXPECT_EQ(svg.find("<script>"), std::string::npos);
  EXPECT_NE(svg.find("&lt;script&gt;"), std::string::npos);
}

TEST(Svg, EventTimelinePutsOneMarkerPerEvent) {
  const std::string svg =
      event_timeline({{1, 0, "#00f", "enrolled"}, {5, 1, "#0f0", "recognised"}}, {"user 1", "user 2"}, 0, 10, "frame");
  EXPECT_EQ(count(svg, "class=\"event\""), 2);
}

}  // namespace
}  // namespace bodyrec::report
