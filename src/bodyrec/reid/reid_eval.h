// `bodyrec eval reid` without the command line: features once per image, then per split train the
// matcher on the training identities (if it learns), describe probes and gallery, rank, score.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <opencv2/core/types.hpp>

#include "bodyrec/reid/appearance_matcher.h"
#include "bodyrec/reid/open_set.h"
#include "bodyrec/reid/reid_split.h"

namespace bodyrec {

struct ReidEvalOptions {
  int train_ids = -1;  // -1: half of the identities present in both cameras
  int splits = 10;
  uint32_t seed = 0;
  bool learn = true;  // false: use each matcher as made (e.g. with a given model), never train it
  bool swap_cameras = false;  // probes from the second camera, gallery from the first
  cv::Size resize;            // every image resampled to this size first (resample.h); empty: as read
  // Also score open-set identification (open_set.h): per split a random half of the test identities
  // (enrolled_identities) is enrolled; the gallery is their other-camera images plus the images of
  // people the probe camera never sees; the probes are every test identity's probe-camera images.
  bool open_set = false;
  void check() const;  // throws UsageError
};

// "WxH" (both whole numbers in 1..8192) -> size; UsageError naming `option` otherwise.
cv::Size parse_image_size(const std::string& text, const std::string& option);

struct ReidEvalResult {
  double rank1 = 0, rank5 = 0, rank10 = 0, rank20 = 0, map = 0;  // means over splits
  std::vector<double> rank1_per_split, map_per_split;
  // At the matcher's threshold (similarity > threshold = same person), over probe x gallery pairs:
  double same_accepted = 0;       // share of same-person pairs accepted
  double different_rejected = 0;  // share of different-person pairs rejected
  int probes = 0, gallery = 0;  // per split (the same in every split)
  int train_ids = 0;
  double ms_per_image = 0;  // features + descriptor + matching per test image, training excluded
  std::string matcher;      // summary() of the last split's matcher
  std::vector<std::string> matcher_per_split;  // summary() of each split's matcher (what it learned)
  // With options.open_set (the threshold figures at the matcher's threshold()): means over splits, and
  // each split's scores.
  OpenSetScores open_set;
  std::vector<OpenSetScores> open_set_per_split;
};

// Makes a fresh matcher for each split (so nothing learned leaks from one split into the next).
using MatcherFactory = std::function<std::unique_ptr<AppearanceMatcher>()>;

// matcher.features() of every image of the data set, in order, each image first resampled to `resize`
// when that is not empty; `ms` (if given) receives the mean extraction time per image. Throws
// InputError naming an image that cannot be read.
std::vector<std::vector<float>> dataset_features(const ReidDataset& data, const AppearanceMatcher& matcher,
                                                 double* ms = nullptr, cv::Size resize = {});

// The same images with the cameras' roles exchanged (the second camera's images become probes).
ReidDataset with_cameras_swapped(ReidDataset data);

// Throws InputError naming the image that cannot be read; UsageError when open_set is asked for and a
// split has fewer than two test identities.
ReidEvalResult evaluate_reid(const ReidDataset& data, const MatcherFactory& make, const ReidEvalOptions& options);

}  // namespace bodyrec
