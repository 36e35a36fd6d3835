// Open-set identification (`bodyrec eval reid --open-set`): only some of the people a probe camera
// sees are enrolled in the gallery, and a matcher must both reject strangers and name enrolled people.
// The detection and identification rate (DIR) at a false-accept rate (FAR) is the usual summary
// (e.g. Liao et al., "Open-set person re-identification", 2014).
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core/mat.hpp>

namespace bodyrec {

// One probe against the gallery.
struct OpenSetProbe {
  double best = 0;         // highest similarity to any gallery image
  bool enrolled = false;   // the probe's identity has a gallery image
  bool own_first = false;  // enrolled, and its own identity's best image is strictly more alike than
                           // every other identity's (a tie counts as not first)
};

// REQUIRES similarity CV_64F, probe_ids.size() rows, gallery_ids.size() >= 1 columns; higher = more alike.
std::vector<OpenSetProbe> open_set_probes(const cv::Mat& similarity, const std::vector<int>& probe_ids,
                                          const std::vector<int>& gallery_ids);

// DIR at `far` (in [0, 1]): with N strangers (probes not enrolled) the threshold is the (k+1)-th highest
// stranger `best`, k = floor(far * N) (so k strangers are accepted, fewer on ties: the FAR is at most
// `far`); DIR = share of enrolled probes that are own_first with best above that threshold. With no
// stranger nothing is rejected (DIR = share own_first); with no enrolled probe it is 0.
double dir_at_far(const std::vector<OpenSetProbe>& probes, double far);

struct OpenSetScores {
  double dir_far1 = 0, dir_far10 = 0;  // DIR at FAR 1 % and 10 %
  // At a fixed threshold (similarity > threshold = same person):
  double dir_at_threshold = 0;     // enrolled probes own_first and accepted
  double far_at_threshold = 0;     // strangers accepted (taken for someone enrolled)
  double missed_at_threshold = 0;  // enrolled probes with nothing accepted (would be enrolled again)
  double rank1_closed = 0;         // enrolled probes own_first, no threshold
  int enrolled = 0, strangers = 0;
};

// All of OpenSetScores for one probe x gallery similarity matrix and the matcher's threshold.
OpenSetScores open_set_scores(const cv::Mat& similarity, const std::vector<int>& probe_ids,
                              const std::vector<int>& gallery_ids, double threshold);

// The enrolled half (rounded down) of `test_ids`, drawn at random for split `index` of `seed` (a
// generator seeded with seed * 1000003 + 1000 + index), ascending.
std::vector<int> enrolled_identities(std::vector<int> test_ids, uint32_t seed, int index);

}  // namespace bodyrec
