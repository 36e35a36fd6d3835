// Training the body shape model, either kind (body_shape.h): the per-pixel body mask network (the default,
// mask_net.h) or the thesis's regression trees with dlib's shape_predictor_trainer (defaults are dlib's;
// the thesis used oversampling 500, nu 0.05, tree depth 2 on 4 images).
#pragma once

#include <optional>
#include <string>

#include "bodyrec/landmarks/body_shape.h"
#include "bodyrec/landmarks/landmark_dataset.h"
#include "bodyrec/landmarks/mask_net.h"

namespace bodyrec {

// How a body shape model places the landmarks: a per-pixel body mask network and its outline, or the
// thesis's ensemble of regression trees.
enum class ShapeMethod { kMaskNet, kTrees };
const char* to_string(ShapeMethod method);                        // "mask-net", "trees"
std::optional<ShapeMethod> parse_shape_method(const std::string& text);  // the inverse

struct ShapeTrainOptions {
  ShapeMethod method = ShapeMethod::kMaskNet;
  MaskNetTrainOptions net;          // method mask-net
  // Method trees (dlib::shape_predictor_trainer):
  int oversampling = 20;          // random initial shapes per training person
  double nu = 0.1;                // learning rate (shrinkage), (0, 1]
  int tree_depth = 4;
  int cascade_depth = 10;
  int trees_per_level = 500;
  int feature_pool_size = 400;    // candidate pixels per cascade level
  int test_splits = 20;           // random split tests tried per tree node
  double lambda = 0.1;            // prior favouring close pixel pairs in split tests
  double padding = 0.0;           // feature pool region grown by this fraction of the landmark box
  int threads = 2;                // training threads of the trees (the network's come from the BLAS library)
  std::string seed;               // random seed ("" = dlib's default, reproducible)
  bool verbose = false;           // progress on stderr (either method)
  void check() const;             // throws UsageError naming the option
};

// Trains on every non-ignored person with landmarks (trees: images converted to grey).
// Throws ProcessingError when there is nothing to train on.
BodyShapeModel train_body_shape(const LandmarkDataset& data, const ShapeTrainOptions& options);

// Writes the model (mask-net: its own header then dlib serialisation; trees: a plain dlib shape_predictor). Throws ProcessingError when the file cannot be written.
void save_body_shape(const BodyShapeModel& model, const std::string& path);

}  // namespace bodyrec
