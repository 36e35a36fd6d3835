// XQDA, Cross-view Quadratic Discriminant Analysis (Liao et al. CVPR 2015): learns a subspace W and a
// metric M in it from pairs of images of the same / different people seen by two cameras, so that
// d(x, z) = (x - z)^T W M W^T (x - z) separates the two kinds of pairs. W holds the generalised
// eigenvectors of (extra-personal, intra-personal) covariance with eigenvalue > 1, M = I - diag(1/lambda)
// in the basis that whitens the intra-personal covariance, so the model folds into one projection P and
// the distance is the squared Euclidean distance between P^T x and P^T z.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "bodyrec/reid/descriptor_view.h"

namespace bodyrec {

// How the subspace and metric are solved for, with Si the (regularised) same-person and Se the
// different-person covariance:
//  kGeneralisedEigen: W = generalised eigenvectors of (Se, Si) with eigenvalue > 1 (the paper's
//      derivation), M = I - diag(1 / eigenvalue) in the basis where W^T Si W = I.
//  kPublishedSvd: as the authors' released XQDA.m computes it: W = left singular vectors of Si^-1 Se
//      (its `[V, S] = svd(...)` returns U) with singular value > 1 (orthonormal, at least one),
//      M = (W^T Si W)^-1 - (W^T Se W)^-1. M is not always positive semi-definite; its negative
//      eigenvalues are dropped (counted in XqdaFit::negative_dims) so the distance stays a squared
//      Euclidean one.
enum class XqdaSolver { kGeneralisedEigen, kPublishedSvd };

struct XqdaOptions {
  double regulariser = 1e-3;  // added to the diagonal of the same-person covariance (the published value)
  int max_dims = 0;           // keep at most this many directions (0 = every one with eigen/singular value > 1)
  XqdaSolver solver = XqdaSolver::kGeneralisedEigen;
  void check() const;
};

// A sample: raw feature, identity, camera (0 = probe side, 1 = gallery side).
struct XqdaSample {
  const std::vector<float>* feature = nullptr;
  int identity = 0;
  int camera = 0;
};

struct XqdaModel {
  cv::Mat projection;      // CV_32F, feature length x dims; embedding = projection^T x
  double threshold = 0;    // squared distance below which two embeddings are called the same person
  cv::Mat rows;            // projection^T, continuous (what embed() reads); set by prepare()

  bool empty() const { return projection.empty(); }
  int input_length() const { return projection.rows; }
  // After setting projection by hand. A new buffer: a copied model shares `rows` with its original, and
  // assigning the transpose expression would write into the shared one.
  void prepare() { rows = cv::Mat(projection.t()); }
  // REQUIRES prepare() called since projection was set; feature.size() == input_length().
  std::vector<float> embed(const std::vector<float>& feature) const;
};

// XQDA in kernel form: all it needs of n training features is their Gram matrix (inner products), so
// models on subsets of one training set (cross-validation) share one Gram matrix.
struct XqdaLabel {
  int identity = 0;
  int camera = 0;
};
struct XqdaFit {
  cv::Mat coefficients;  // CV_64F n x k: embedding of x = coefficients^T (inner products of x with the samples)
  cv::Mat embedded;      // CV_64F n x k: the training samples' embeddings
  double threshold = 0;  // balanced-error squared distance over the training cross-camera pairs
  int dims = 0;           // directions kept by the solver (before negative ones are dropped)
  int negative_dims = 0;  // kPublishedSvd: eigenvalues of M below 0, dropped
};

// REQUIRES gram CV_64F n x n symmetric, labels.size() == n, samples from both cameras, at least two
// identities in both. Throws ProcessingError when the data cannot train a model.
XqdaFit fit_xqda(const cv::Mat& gram, const std::vector<XqdaLabel>& labels, const XqdaOptions& options = {});

// The Gram matrix (CV_64F) of float features: rows of `features` (CV_32F n x d).
cv::Mat gram_matrix(const cv::Mat& features);

// REQUIRES samples from both cameras, at least two identities present in both, all features the same
// length. Same-person pairs are (camera 0, camera 1) pairs with equal identity; different-person pairs
// all other cross-camera pairs. Throws ProcessingError when the data cannot train a model.
XqdaModel train_xqda(const std::vector<XqdaSample>& samples, const XqdaOptions& options = {});

// Several XQDA models, each on its own consecutive slice of the input, fused by summing their distances
// each divided by its own threshold: the embedding concatenates the slices' embeddings scaled by
// 1 / sqrt(threshold), so the fused distance is still one squared Euclidean distance.
struct XqdaEnsemble {
  std::vector<XqdaModel> parts;
  double threshold = 0;  // fused squared distance below which two images are called the same person
  std::string id;        // short fingerprint (part of the descriptor version)
  std::string features;  // what the input features are (set by the matcher that trains it, e.g. "lomo4")
  std::string variant;   // which of the matcher's variants the parts are (its business; may be empty)
  cv::Mat feature_mean;  // optional CV_32F row: a training-feature mean the matcher centres inputs with

  bool empty() const { return parts.empty(); }
  int input_length() const;
  int embed_length() const;
  // REQUIRES feature.size() == input_length().
  std::vector<float> embed(const std::vector<float>& feature) const;
  // Writes / reads cv::FileStorage YAML (format_version 4: projections as int8 with a float scale per
  // column, in base64; a `.gz` name compresses). Training already rounds the projections so, so a saved
  // and reloaded model embeds exactly as the trained one. load also reads format_version 3 (float16
  // projections); it throws InputError naming the file and the field at fault, and refuses older
  // versions (train again). save REQUIRES features set (else ProcessingError).
  void save(const std::string& path) const;
  static XqdaEnsemble load(const std::string& path);
};

// Trains one model per slice (consecutive slices of the given lengths, summing to the feature length).
// The fused threshold is calibrated on people the model has not seen: cross-validation over the
// identities present in both cameras gives the balanced-error threshold of held-out pairs, in units of
// each model's median different-person distance on its own training pairs, for models trained on 1/2
// and 3/4 of the identities; that is extrapolated linearly to all of them (upwards only) and applied to
// the full model's own scale. With fewer than 12 such identities it is the balanced-error threshold of
// the training pairs, which is far too strict for new people.
XqdaEnsemble train_xqda_ensemble(const std::vector<XqdaSample>& samples, const std::vector<int>& slice_lengths,
                                 const XqdaOptions& options = {});
// The same with `slices` equal slices.
XqdaEnsemble train_xqda_ensemble(const std::vector<XqdaSample>& samples, int slices, const XqdaOptions& options = {});

// Squared Euclidean distance between two embeddings (REQUIRES equal lengths).
double squared_distance(DescriptorView a, DescriptorView b);

}  // namespace bodyrec
