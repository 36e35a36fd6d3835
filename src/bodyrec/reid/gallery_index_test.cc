#include "bodyrec/reid/gallery_index.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "bodyrec/reid/stripe_features.h"
#include "bodyrec/store/gallery.h"
#include "test_support.h"

namespace bodyrec {
namespace {

// A body of two colours whose crop spans `top_m` down to the floor (lower top: only the legs show).
std::vector<float> stripes_of(const cv::Scalar& shirt, const cv::Scalar& trousers, double top_m, int seed) {
  PersonImage p;
  const int rows = static_cast<int>(top_m * 100);
  p.bgr = cv::Mat(rows, 60, CV_8UC3, cv::Scalar(0, 0, 0));
  cv::rectangle(p.bgr, cv::Rect(5, 0, 50, rows / 2), shirt, cv::FILLED);
  cv::rectangle(p.bgr, cv::Rect(10, rows / 2, 40, rows - rows / 2), trousers, cv::FILLED);
  cv::Mat noise(p.bgr.size(), CV_8UC3);
  cv::RNG rng(static_cast<uint64_t>(seed));
  rng.fill(noise, cv::RNG::UNIFORM, 0, 40);
  p.bgr += noise;
  cv::Mat grey;
  cv::cvtColor(p.bgr, grey, cv::COLOR_BGR2GRAY);
  p.mask = grey > 0;
  for (int y = 0; y < rows; ++y) p.row_height_m.push_back(static_cast<float>(top_m - 0.01 * (y + 0.5)));
  return stripe_features(p);
}

std::vector<std::vector<float>> some_stripes() {
  const cv::Scalar colours[] = {{30, 30, 210}, {160, 60, 20}, {40, 180, 40}, {30, 210, 220}, {200, 200, 200}};
  std::vector<std::vector<float>> out;
  for (int i = 0; i < 10; ++i)
    out.push_back(stripes_of(colours[i % 5], colours[(i + 2) % 5], i == 7 ? 0.5 : 1.5 + 0.05 * i, i + 1));
  return out;
}

TEST(StripeIndex, GivesTheDistancesOfStripeDistance) {
  const auto d = some_stripes();
  StripeIndex index;
  for (const auto& x : d) index.push_back(x);
  ASSERT_EQ(index.size(), d.size());
  std::vector<std::optional<double>> out;
  int unmatched = 0;
  for (const auto& probe : d) {
    index.distances(probe, out);
    ASSERT_EQ(out.size(), d.size());
    for (size_t i = 0; i < d.size(); ++i) {
      const std::optional<double> want = stripe_distance(probe, d[i]);
      ASSERT_EQ(out[i].has_value(), want.has_value()) << i;
      if (want) {
        EXPECT_NEAR(*out[i], *want, 1e-5) << i;
      }
      unmatched += !want;
    }
  }
  // The 0.5 m crop shows bands 0-2 only: fewer than min_common 4, compared with anyone (9 x 2 pairs)
  // or with itself.
  EXPECT_EQ(unmatched, 2 * 9 + 1);
  index.distances(d[3], out);
  EXPECT_NEAR(*out[3], 0.0, 1e-5);
  EXPECT_GT(*out[4], 2.5);
}

TEST(StripeIndex, SetAndSwapRemoveKeepRowsInStep) {
  const auto d = some_stripes();
  StripeIndex index;
  for (int i = 0; i < 4; ++i) index.push_back(d[static_cast<size_t>(i)]);
  index.set(1, d[5]);
  index.swap_remove(0);  // row 3 moves to row 0
  ASSERT_EQ(index.size(), 3u);
  std::vector<std::optional<double>> out;
  index.distances(d[3], out);
  EXPECT_NEAR(*out[0], 0.0, 1e-5);
  EXPECT_NEAR(*out[1], *stripe_distance(d[3], d[5]), 1e-5);
  EXPECT_NEAR(*out[2], *stripe_distance(d[3], d[2]), 1e-5);
  EXPECT_THROW(index.push_back(std::vector<float>(10, 0.f)), cv::Exception);
}

TEST(DescriptorIndex, EveryMatchersIndexAgreesWithItsSimilarity) {
  const auto d = some_stripes();
  for (const char* name : {"stripes", "lomo"}) {
    auto matcher = make_matcher(name);
    std::vector<std::vector<float>> rows = d;
    if (std::string(name) == "lomo")  // any equal-length vectors do for a distance check
      for (auto& r : rows) r.resize(200);
    auto index = matcher->make_index();
    for (const auto& r : rows) index->push_back(r);
    std::vector<double> out;
    index->similarities(rows[2], out);
    ASSERT_EQ(out.size(), rows.size()) << name;
    for (size_t i = 0; i < rows.size(); ++i) EXPECT_NEAR(out[i], matcher->similarity(rows[2], rows[i]), 1e-4) << name << " " << i;
  }
}

struct GalleryFixture {
  testing::TempDir dir;
  std::unique_ptr<Gallery> gallery;
  std::unique_ptr<AppearanceMatcher> matcher = make_matcher("stripes");
  GalleryFixture() {
    GalleryOptions g;
    g.create = true;
    g.sync_full = false;
    gallery = std::make_unique<Gallery>((dir.path() / "g.db").string(), g);
  }
  GalleryScan scan(View view, const std::vector<float>& d, const std::string& descriptor = "stripes/stripes2") {
    GalleryScan s;
    s.view = view;
    s.features = cv::Mat(d, true).reshape(1, 1);
    s.descriptor = descriptor;
    s.quality = 0.5;
    return s;
  }
  GalleryIndex index() {
    return GalleryIndex(
        *gallery, *matcher, [](const GalleryEntry& e) { return e.descriptor == "stripes/stripes2"; },
        [](const GalleryEntry& e) { return DescriptorView(e.features.ptr<float>(), e.features.total()); });
  }
};

TEST(GalleryIndex, FollowsEnrolmentsViewsAndErasures) {
  GalleryFixture f;
  const auto d = some_stripes();
  const UserId a = f.gallery->enrol(f.scan(View::F, d[0]));
  const UserId b = f.gallery->enrol(f.scan(View::F, d[1]));
  f.gallery->put_scan(b, f.scan(View::B, d[2]));
  f.gallery->enrol(f.scan(View::F, d[3], "kaze/kaze1"));  // another matcher's: not indexed
  GalleryIndex index = f.index();
  EXPECT_EQ(index.size(), 3u);
  std::vector<double> out;
  index.search(View::F, d[1], out);
  ASSERT_EQ(out.size(), 2u);
  ASSERT_EQ(index.slots(View::F).size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    const UserId u = index.user(index.slots(View::F)[i]);
    EXPECT_NEAR(out[i], f.matcher->similarity(d[1], u == a ? d[0] : d[1]), 1e-4);
  }
  index.search(View::B, d[2], out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(index.user(index.slots(View::B)[0]), b);
  EXPECT_NEAR(out[0], 0.0, 1e-4);

  // A new view of a, then a replaced view of b: update() takes them in.
  f.gallery->put_scan(a, f.scan(View::B, d[4]));
  index.update(a);
  GalleryScan sharper = f.scan(View::F, d[5]);
  sharper.quality = 0.9;
  f.gallery->put_scan(b, sharper);
  index.update(b);
  EXPECT_EQ(index.size(), 4u);
  index.search(View::F, d[5], out);
  for (size_t i = 0; i < out.size(); ++i)
    if (index.user(index.slots(View::F)[i]) == b) {
      EXPECT_NEAR(out[i], 0.0, 1e-4);
    }

  // Forgetting a removes its rows; b's stay and keep their slot.
  f.gallery->forget(a);
  index.update(a);
  EXPECT_EQ(index.size(), 2u);
  index.search(View::B, d[2], out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(index.user(index.slots(View::B)[0]), b);
  // reload() from the cache gives the same rows.
  index.reload();
  EXPECT_EQ(index.size(), 2u);
  EXPECT_EQ(index.slots(View::F).size(), 1u);
}

}  // namespace
}  // namespace bodyrec
