// Choosing among fixed XQDA variants by cross-validation inside the training data only: the training
// identities are split into folds, each fold's people are held out in turn, every variant is trained on
// the others and scored on them. Nothing outside the given samples is looked at, so a figure measured on
// other people afterwards was never used to choose.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "bodyrec/reid/xqda.h"

namespace bodyrec {

// A variant: one XQDA model per part, each on the concatenation of the listed feature blocks, fused as
// XqdaEnsemble fuses (each part's distance over its own training threshold, summed).
struct XqdaVariant {
  std::string name;
  std::vector<std::vector<int>> parts;  // block indices per part
};

struct XqdaSelection {
  int chosen = 0;             // index of the variant with the best score (the first one on ties)
  std::vector<double> score;  // per variant: mean over folds and both directions of the held-out mAP
};

// block_grams[b]: Gram matrix (CV_64F n x n) of feature block b over the n training samples.
// Folds: the identities seen by both cameras, in an order drawn from a fixed generator, dealt round
// robin; the held-out people's camera-0 images are ranked against their camera-1 images and the other
// way round (mAP, cmc.h). Samples of identities seen by one camera only are always in the fitting part.
// REQUIRES at least 2 * folds identities in both cameras (else UsageError), every block index valid.
XqdaSelection select_xqda_variant(const std::vector<cv::Mat>& block_grams, const std::vector<XqdaLabel>& labels,
                                  const std::vector<XqdaVariant>& variants, int folds,
                                  const XqdaOptions& options = {});

}  // namespace bodyrec
