#include "bodyrec/reid/open_set.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <set>

namespace bodyrec {
namespace {

double share(int count, int total) { return total > 0 ? static_cast<double>(count) / total : 0.0; }

}  // namespace

std::vector<OpenSetProbe> open_set_probes(const cv::Mat& similarity, const std::vector<int>& probe_ids,
                                          const std::vector<int>& gallery_ids) {
  CV_Assert(similarity.type() == CV_64F && similarity.rows == static_cast<int>(probe_ids.size()) &&
            similarity.cols == static_cast<int>(gallery_ids.size()) && similarity.cols > 0);
  const double lowest = -std::numeric_limits<double>::infinity();
  std::vector<OpenSetProbe> probes;
  for (int p = 0; p < similarity.rows; ++p) {
    const double* row = similarity.ptr<double>(p);
    double own = lowest, other = lowest;
    OpenSetProbe probe;
    for (int g = 0; g < similarity.cols; ++g) {
      if (gallery_ids[static_cast<size_t>(g)] == probe_ids[static_cast<size_t>(p)]) {
        probe.enrolled = true;
        own = std::max(own, row[g]);
      } else {
        other = std::max(other, row[g]);
      }
    }
    probe.best = std::max(own, other);
    probe.own_first = probe.enrolled && own > other;
    probes.push_back(probe);
  }
  return probes;
}

double dir_at_far(const std::vector<OpenSetProbe>& probes, double far) {
  std::vector<double> strangers;
  int enrolled = 0;
  for (const auto& p : probes) {
    if (p.enrolled) ++enrolled;
    else strangers.push_back(p.best);
  }
  std::sort(strangers.begin(), strangers.end(), std::greater<>());
  const size_t k = static_cast<size_t>(std::floor(far * static_cast<double>(strangers.size()) + 1e-9));
  const double threshold = k < strangers.size() ? strangers[k] : -std::numeric_limits<double>::infinity();
  int detected = 0;
  for (const auto& p : probes) detected += p.own_first && p.best > threshold;
  return share(detected, enrolled);
}

OpenSetScores open_set_scores(const cv::Mat& similarity, const std::vector<int>& probe_ids,
                              const std::vector<int>& gallery_ids, double threshold) {
  const std::vector<OpenSetProbe> probes = open_set_probes(similarity, probe_ids, gallery_ids);
  OpenSetScores s;
  int first = 0, detected = 0, false_accepts = 0, missed = 0;
  for (const auto& p : probes) {
    const bool accepted = p.best > threshold;
    if (p.enrolled) {
      ++s.enrolled;
      first += p.own_first;
      detected += p.own_first && accepted;
      missed += !accepted;
    } else {
      ++s.strangers;
      false_accepts += accepted;
    }
  }
  s.dir_far1 = dir_at_far(probes, 0.01);
  s.dir_far10 = dir_at_far(probes, 0.10);
  s.dir_at_threshold = share(detected, s.enrolled);
  s.far_at_threshold = share(false_accepts, s.strangers);
  s.missed_at_threshold = share(missed, s.enrolled);
  s.rank1_closed = share(first, s.enrolled);
  return s;
}

std::vector<int> enrolled_identities(std::vector<int> test_ids, uint32_t seed, int index) {
  std::sort(test_ids.begin(), test_ids.end());
  test_ids.erase(std::unique(test_ids.begin(), test_ids.end()), test_ids.end());
  std::mt19937 rng(seed * 1000003u + 1000u + static_cast<uint32_t>(index));
  for (size_t i = test_ids.size(); i > 1; --i) std::swap(test_ids[i - 1], test_ids[rng() % static_cast<uint32_t>(i)]);
  test_ids.resize(test_ids.size() / 2);
  std::sort(test_ids.begin(), test_ids.end());
  return test_ids;
}

}  // namespace bodyrec
