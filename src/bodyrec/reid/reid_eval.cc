#include "bodyrec/reid/reid_eval.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <set>
#include <string_view>
#include <utility>

#include <opencv2/imgcodecs.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/core/parse_number.h"
#include "bodyrec/reid/cmc.h"
#include "bodyrec/reid/resample.h"

namespace bodyrec {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

// The open-set scores of one split (ReidEvalOptions::open_set) from its closed-set similarity matrix
// (every split probe against every split gallery image).
OpenSetScores open_set_split(const ReidDataset& data, const ReidSplit& split, const cv::Mat& similarity,
                             const std::vector<int>& probe_ids, double threshold, uint32_t seed, int index) {
  std::vector<int> test_ids = probe_ids;
  std::sort(test_ids.begin(), test_ids.end());
  test_ids.erase(std::unique(test_ids.begin(), test_ids.end()), test_ids.end());
  if (test_ids.size() < 2)
    throw UsageError("--open-set needs at least two test identities per split (split " + std::to_string(index) +
                     " has " + std::to_string(test_ids.size()) + "): lower --train-ids");
  const std::vector<int> enrolled = enrolled_identities(test_ids, seed, index);
  const std::set<int> enrolled_set(enrolled.begin(), enrolled.end());
  std::vector<char> probe_camera_sees(data.identities.size(), 0);
  for (const auto& image : data.images)
    if (image.camera == 0) probe_camera_sees[static_cast<size_t>(image.identity)] = 1;
  std::vector<int> columns, gallery_ids;
  for (size_t g = 0; g < split.gallery.size(); ++g) {
    const int id = data.images[static_cast<size_t>(split.gallery[g])].identity;
    if (enrolled_set.count(id) || !probe_camera_sees[static_cast<size_t>(id)])
      columns.push_back(static_cast<int>(g)), gallery_ids.push_back(id);
  }
  cv::Mat open(similarity.rows, static_cast<int>(columns.size()), CV_64F);
  for (int p = 0; p < similarity.rows; ++p)
    for (int c = 0; c < open.cols; ++c) open.at<double>(p, c) = similarity.at<double>(p, columns[static_cast<size_t>(c)]);
  return open_set_scores(open, probe_ids, gallery_ids, threshold);
}

}  // namespace

cv::Size parse_image_size(const std::string& text, const std::string& option) {
  const auto x = text.find('x');
  const auto side = [&](std::string_view part) {
    const auto v = parse_integer(part);
    return v && *v >= 1 && *v <= 8192 && part.find_first_of(" \t+") == std::string_view::npos ? static_cast<int>(*v) : 0;
  };
  const int w = x == std::string::npos ? 0 : side(std::string_view(text).substr(0, x));
  const int h = x == std::string::npos ? 0 : side(std::string_view(text).substr(x + 1));
  if (w == 0 || h == 0)
    throw UsageError(option + " must be WxH with whole numbers in 1..8192, e.g. 128x256 (got '" + text + "')");
  return {w, h};
}

ReidDataset with_cameras_swapped(ReidDataset data) {
  std::swap(data.cameras[0], data.cameras[1]);
  for (auto& image : data.images) image.camera = 1 - image.camera;
  return data;
}

std::vector<std::vector<float>> dataset_features(const ReidDataset& data, const AppearanceMatcher& matcher,
                                                 double* ms, cv::Size resize) {
  std::vector<std::vector<float>> features(data.images.size());
  double total_ms = 0;
  for (size_t i = 0; i < data.images.size(); ++i) {
    const std::string path = (std::filesystem::path(data.root) / data.images[i].path).string();
    PersonImage image;
    image.bgr = cv::imread(path, cv::IMREAD_COLOR);
    if (image.bgr.empty()) throw InputError(path + ": cannot read the image");
    if (!resize.empty()) image.bgr = resample_image(image.bgr, resize);
    const auto t = Clock::now();
    features[i] = matcher.features(image);
    total_ms += ms_since(t);
  }
  if (ms) *ms = data.images.empty() ? 0.0 : total_ms / static_cast<double>(data.images.size());
  return features;
}

void ReidEvalOptions::check() const {
  if (splits < 1) throw OptionError("ReidEvalOptions", "splits", "must be >= 1");
  if (train_ids < -1) throw OptionError("ReidEvalOptions", "train_ids", "must be >= 0");
  if (resize.width < 0 || resize.height < 0 || (resize.width == 0) != (resize.height == 0))
    throw OptionError("ReidEvalOptions", "resize", "must have a positive width and height");
}

ReidEvalResult evaluate_reid(const ReidDataset& given, const MatcherFactory& make, const ReidEvalOptions& options) {
  options.check();
  const ReidDataset data = options.swap_cameras ? with_cameras_swapped(given) : given;
  ReidEvalResult result;
  result.train_ids = options.train_ids >= 0 ? options.train_ids : static_cast<int>(data.in_both.size()) / 2;
  const int test_ids = static_cast<int>(data.in_both.size()) - result.train_ids;
  if (options.open_set && test_ids < 2)
    throw UsageError("--open-set needs at least two test identities per split (" + std::to_string(test_ids) +
                     " left after " + std::to_string(result.train_ids) + " for training)");
  // Features do not depend on the split: compute them once per image.
  double feature_ms_per_image = 0;
  const std::vector<std::vector<float>> features = dataset_features(data, *make(), &feature_ms_per_image, options.resize);
  double match_ms_per_image = 0;
  for (int s = 0; s < options.splits; ++s) {
    const ReidSplit split = make_reid_split(data, result.train_ids, options.seed, s);
    std::unique_ptr<AppearanceMatcher> matcher = make();
    if (options.learn && !split.train.empty()) {
      std::vector<TrainingSample> samples;
      for (int i : split.train)
        samples.push_back({&features[static_cast<size_t>(i)], data.images[i].identity, data.images[i].camera});
      matcher->train(samples);
    }
    const auto t = Clock::now();
    std::vector<std::vector<float>> probe_d, gallery_d;
    std::vector<int> probe_ids, gallery_ids;
    for (int i : split.probes) probe_d.push_back(matcher->descriptor(features[i])), probe_ids.push_back(data.images[i].identity);
    for (int i : split.gallery)
      gallery_d.push_back(matcher->descriptor(features[i])), gallery_ids.push_back(data.images[i].identity);
    cv::Mat similarity(static_cast<int>(probe_d.size()), static_cast<int>(gallery_d.size()), CV_64F);
    for (int p = 0; p < similarity.rows; ++p)
      for (int g = 0; g < similarity.cols; ++g) similarity.at<double>(p, g) = matcher->similarity(probe_d[p], gallery_d[g]);
    match_ms_per_image += ms_since(t) / static_cast<double>(probe_d.size() + gallery_d.size());
    const RankingScores scores = ranking_scores(similarity, probe_ids, gallery_ids, 20);
    double same = 0, same_ok = 0, diff = 0, diff_ok = 0;
    for (int p = 0; p < similarity.rows; ++p)
      for (int g = 0; g < similarity.cols; ++g) {
        const bool accepted = similarity.at<double>(p, g) > matcher->threshold();
        if (probe_ids[p] == gallery_ids[g]) same += 1, same_ok += accepted;
        else diff += 1, diff_ok += !accepted;
      }
    result.same_accepted += same > 0 ? same_ok / same : 0.0;
    result.different_rejected += diff > 0 ? diff_ok / diff : 0.0;
    result.rank1 += scores.cmc[0];
    result.rank5 += scores.cmc[4];
    result.rank10 += scores.cmc[9];
    result.rank20 += scores.cmc[19];
    result.map += scores.map;
    result.rank1_per_split.push_back(scores.cmc[0]);
    result.map_per_split.push_back(scores.map);
    if (options.open_set) {
      const OpenSetScores o = open_set_split(data, split, similarity, probe_ids, matcher->threshold(), options.seed, s);
      result.open_set_per_split.push_back(o);
      OpenSetScores& m = result.open_set;
      m.dir_far1 += o.dir_far1, m.dir_far10 += o.dir_far10, m.rank1_closed += o.rank1_closed;
      m.dir_at_threshold += o.dir_at_threshold, m.far_at_threshold += o.far_at_threshold;
      m.missed_at_threshold += o.missed_at_threshold;
      m.enrolled = o.enrolled, m.strangers = o.strangers;
    }
    result.probes = static_cast<int>(split.probes.size());
    result.gallery = static_cast<int>(split.gallery.size());
    result.matcher = matcher->summary();
    result.matcher_per_split.push_back(result.matcher);
  }
  const double n = options.splits;
  result.rank1 /= n, result.rank5 /= n, result.rank10 /= n, result.rank20 /= n, result.map /= n;
  result.same_accepted /= n, result.different_rejected /= n;
  OpenSetScores& m = result.open_set;
  m.dir_far1 /= n, m.dir_far10 /= n, m.rank1_closed /= n;
  m.dir_at_threshold /= n, m.far_at_threshold /= n, m.missed_at_threshold /= n;
  result.ms_per_image = feature_ms_per_image + match_ms_per_image / n;
  return result;
}

}  // namespace bodyrec
