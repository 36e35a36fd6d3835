// The LOMO-based matchers of make_matcher (appearance_matcher.h):
//  kPublished ("lomo-xqda"): the published recipe of Liao et al. 2015, LOMO (Retinex colours) + one XQDA.
//  kDefault ("default"): variants of LOMO and GOG features with XQDA, fused; train() chooses the variant
//      by cross-validation over the training people only (xqda_selection.h), then trains it on all of them.
//  kDefaultFull ("default-full"): the same on the full features (no count sketch) with up to 100 dimensions
//      per part: better on VIPeR (docs/benchmarks.md), but its model is about 7.7 MB, too large to ship:
//      train-reid makes it.
//  kUnlearned ("lomo"): mirror-averaged LOMO, squared Euclidean distance, no model.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "bodyrec/reid/appearance_matcher.h"
#include "bodyrec/reid/xqda.h"
#include "bodyrec/reid/xqda_selection.h"

namespace bodyrec {

enum class LearnedMatcherKind { kPublished, kDefault, kDefaultFull, kUnlearned };

// The file name under which the default matcher's model is shipped (models/README.md; model_files.h).
inline constexpr const char* kShippedReidModel = "reid-default.yml.gz";

// The default matcher's variants, in the order train() compares them (the first wins ties), over the
// blocks of its features: 0 LOMO colours after Retinex, 1-2 SILTP R=3/R=5, 3-6 the same parts and the
// colours as seen, mirror-averaged (3 as seen, 4 Retinex, 5-6 SILTP), 7 GOG in four colour spaces.
std::vector<XqdaVariant> default_reid_variants();

// Folds of the default matcher's inner cross-validation (fewer when fewer than 8 people are seen by both
// cameras: each fold holds out two at least; below 4 the first variant is trained without choosing); its
// XQDA keeps at most this many dimensions per part (the published recipe keeps every one with
// eigenvalue > 1), on features count-sketched to a third of their length, which keeps the model file
// near 1 MB (learned_matcher.cc).
inline constexpr int kDefaultSelectionFolds = 4;
inline constexpr int kDefaultMaxDims = 33;
inline constexpr int kFullMaxDims = 100;  // default-full: the same variants on the unsketched features

// `model` empty: untrained (the kinds but kUnlearned then need train() before descriptor(), which throws
// ProcessingError otherwise). `source` names where the model came from, for errors: InputError when
// the model was trained on other features or for another kind.
std::unique_ptr<AppearanceMatcher> make_learned_matcher(LearnedMatcherKind kind, XqdaEnsemble model = {},
                                                        const std::string& source = "");

}  // namespace bodyrec
