#include "bodyrec/reid/xqda_selection.h"

#include <algorithm>
#include <map>
#include <random>
#include <set>

#include <opencv2/core.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/reid/cmc.h"
#include "bodyrec/reid/xqda_kernel.h"

namespace bodyrec {
namespace {

using namespace xqda_detail;

// Held-out distances of one part for one fold: camera-0 x camera-1 images of the held-out people,
// already divided by the part's training threshold.
cv::Mat part_distances(const cv::Mat& gram, const std::vector<XqdaLabel>& labels, const std::vector<int>& fit_rows,
                       const std::vector<int>& probes, const std::vector<int>& gallery, const XqdaOptions& options) {
  std::vector<XqdaLabel> fit_labels;
  for (int r : fit_rows) fit_labels.push_back(labels[static_cast<size_t>(r)]);
  const XqdaFit fit = fit_xqda(sub_gram(gram, fit_rows, fit_rows), fit_labels, options);
  const cv::Mat d = row_distances(embed_others(gram, fit_rows, fit, probes), embed_others(gram, fit_rows, fit, gallery));
  return d / std::max(fit.threshold, 1e-12);
}

double both_directions_map(const cv::Mat& distance, const std::vector<int>& probe_ids,
                           const std::vector<int>& gallery_ids) {
  const cv::Mat similarity = -distance;
  const double forward = ranking_scores(similarity, probe_ids, gallery_ids, 1).map;
  const double backward = ranking_scores(cv::Mat(similarity.t()), gallery_ids, probe_ids, 1).map;
  return 0.5 * (forward + backward);
}

}  // namespace

XqdaSelection select_xqda_variant(const std::vector<cv::Mat>& block_grams, const std::vector<XqdaLabel>& labels,
                                  const std::vector<XqdaVariant>& variants, int folds, const XqdaOptions& options) {
  if (variants.empty()) throw UsageError("XQDA selection: no variant to choose from");
  if (folds < 2) throw UsageError("XQDA selection: folds must be >= 2");
  const size_t n = labels.size();
  for (const cv::Mat& g : block_grams) CV_Assert(g.type() == CV_64F && g.rows == static_cast<int>(n) && g.cols == g.rows);
  std::map<int, int> cameras;  // identity -> bit mask of cameras
  for (const auto& l : labels) cameras[l.identity] |= 1 << (l.camera == 0 ? 0 : 1);
  std::vector<int> both;
  for (const auto& [id, mask] : cameras)
    if (mask == 3) both.push_back(id);
  if (static_cast<int>(both.size()) < 2 * folds)
    throw UsageError("XQDA selection: " + std::to_string(both.size()) + " identities in both cameras, need at least " +
                     std::to_string(2 * folds) + " for " + std::to_string(folds) + " folds");
  // Fisher-Yates with a fixed generator: the same samples always give the same folds.
  std::mt19937 rng(20240043u);
  for (size_t i = both.size() - 1; i > 0; --i) std::swap(both[i], both[rng() % static_cast<uint32_t>(i + 1)]);
  std::map<int, int> fold_of;
  for (size_t i = 0; i < both.size(); ++i) fold_of[both[i]] = static_cast<int>(i) % folds;

  // Each distinct part (block list) is trained once per fold and shared by the variants that use it.
  std::vector<std::vector<int>> parts;
  for (const auto& v : variants)
    for (const auto& p : v.parts) {
      for (int b : p)
        if (b < 0 || b >= static_cast<int>(block_grams.size())) throw UsageError("XQDA selection: bad block index");
      if (std::find(parts.begin(), parts.end(), p) == parts.end()) parts.push_back(p);
    }
  std::vector<cv::Mat> part_grams;
  for (const auto& p : parts) {
    cv::Mat g = cv::Mat::zeros(static_cast<int>(n), static_cast<int>(n), CV_64F);
    for (int b : p) g += block_grams[static_cast<size_t>(b)];
    part_grams.push_back(g);
  }

  XqdaSelection result;
  result.score.assign(variants.size(), 0.0);
  for (int fold = 0; fold < folds; ++fold) {
    std::vector<int> fit_rows, probes, gallery, probe_ids, gallery_ids;
    for (size_t i = 0; i < n; ++i) {
      const auto it = fold_of.find(labels[i].identity);
      if (it == fold_of.end() || it->second != fold) {
        fit_rows.push_back(static_cast<int>(i));
      } else if (labels[i].camera == 0) {
        probes.push_back(static_cast<int>(i)), probe_ids.push_back(labels[i].identity);
      } else {
        gallery.push_back(static_cast<int>(i)), gallery_ids.push_back(labels[i].identity);
      }
    }
    std::vector<cv::Mat> distances;
    for (const cv::Mat& g : part_grams) distances.push_back(part_distances(g, labels, fit_rows, probes, gallery, options));
    for (size_t v = 0; v < variants.size(); ++v) {
      cv::Mat fused = cv::Mat::zeros(static_cast<int>(probes.size()), static_cast<int>(gallery.size()), CV_64F);
      for (const auto& p : variants[v].parts)
        fused += distances[static_cast<size_t>(std::find(parts.begin(), parts.end(), p) - parts.begin())];
      result.score[v] += both_directions_map(fused, probe_ids, gallery_ids) / folds;
    }
  }
  result.chosen = static_cast<int>(std::max_element(result.score.begin(), result.score.end()) - result.score.begin());
  return result;
}

}  // namespace bodyrec
