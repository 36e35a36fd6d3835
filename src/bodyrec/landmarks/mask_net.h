// Body contours from a per-pixel body mask: a small fully convolutional network (a U-Net trained with
// dlib's DNN on the CPU, its convolutions computed by oneDNN: dnnl_con.h; run with oneDNN: unet_runner.h)
// labels every pixel of a person's box as body or background, and the landmarks are that mask's outline
// sampled exactly as the training contours were (contour_from_mask: point 0 at the head top, clockwise,
// equally spaced by arc length). Regressing the N coordinates directly (the thesis's regression trees)
// makes points slide along the outline wherever a leg or arm gap changes its length; a mask carries the
// gap, and the numbering follows from it (docs/benchmarks.md, "Body-contour landmarks").
#pragma once

#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "bodyrec/core/geometry.h"
#include "bodyrec/landmarks/landmark_dataset.h"

namespace bodyrec {

constexpr int kMaxNetworks = 8;  // networks averaged in one model

struct MaskNetTrainOptions {
  int input_width = 24;            // the box is resampled to input_width x input_height (multiples of 8)
  int input_height = 72;
  int iterations = 3000;           // mini-batches
  int batch = 16;                  // crops per mini-batch
  double learning_rate = 1.2e-2;   // peak of the schedule (10 % warm-up, then cosine to ~0)
  double weight_decay = 0;         // Adam's L2 penalty on the weights (5e-4: docs/benchmarks.md)
  double threshold = 0.5;          // logit above which a pixel is body (stored in the model)
  double box_jitter = 0.03;        // std-dev of the box's shift (x; half of it in y) and log-size, per box side
  unsigned seed = 0;               // augmentation draws (network k: seed + k)
  int networks = 2;                // trained side by side; fitting averages their logits
  bool verbose = false;            // loss every 10 % of the run on stderr
  void check() const;              // throws UsageError naming the option
};

// Not thread-safe (the forward passes reuse the network's buffers): use one per thread.
class BodyMaskNet {
 public:
  // Reads a model written by save(). Throws InputError naming `name` when the stream is not one.
  BodyMaskNet(std::istream& in, const std::string& name);
  ~BodyMaskNet();
  BodyMaskNet(BodyMaskNet&&) noexcept;
  BodyMaskNet& operator=(BodyMaskNet&&) noexcept;

  // True when `in` starts with a mask-net header; the stream is rewound to where it was.
  static bool recognise(std::istream& in);
  void save(std::ostream& out) const;

  // The network's per-pixel body logits of `box` in `bgr` (CV_8UC3): input_height x input_width, CV_32F.
  // A model of several networks gives the mean of theirs; they run side by side, one OpenCV thread each
  // (unet_runner.h).
  cv::Mat logits(const cv::Mat& bgr, const Box& box) const;
  // The same from dlib's own forward pass (slower): the check that the network OpenCV runs is dlib's.
  cv::Mat reference_logits(const cv::Mat& bgr, const Box& box) const;
  // What fit() thresholds: with mirror averaging (the default), the mean of logits() on the
  // crop and, flipped back, on its mirror image (the network learnt both; their mean is steadier where
  // it is unsure, e.g. between the legs); without, logits().
  cv::Mat fitting_logits(const cv::Mat& bgr, const Box& box) const;
  // A fitting option, not saved with the model: on after loading or training.
  void set_mirror_average(bool on);
  bool mirror_average() const;
  // A fitting option, not saved with the model: cut a slit between the legs where the logits dip
  // (leg_gap.h) before tracing each outline; on after loading or training.
  void set_leg_slit(bool on);
  bool leg_slit() const;
  // `landmarks` points on the outline of the body mask's largest component, numbered as contour_from_mask.
  // The mask is fitting_logits() (upsampled, cubic, to the box but at most twice the network's rows tall;
  // the outline is scaled to the box) above the threshold, with the slit between the legs when
  // leg_slit(); when no pixel passes, the pixels within 1 of the highest.
  std::vector<cv::Point2d> fit(const cv::Mat& bgr, const Box& box, int landmarks) const;
  // The same outline at several thresholds (threshold() + each offset) from one network batch: one
  // outline per offset, in order. REQUIRES: offsets not empty.
  std::vector<std::vector<cv::Point2d>> fit_at(const cv::Mat& bgr, const Box& box, int landmarks,
                                               const std::vector<double>& threshold_offsets) const;

  cv::Size input_size() const;
  int networks() const;  // 1 to kMaxNetworks
  double threshold() const;
  void set_threshold(double logit);  // REQUIRES: finite

 private:
  friend BodyMaskNet train_body_mask_net(const LandmarkDataset&, const MaskNetTrainOptions&);
  BodyMaskNet();
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Trains on every non-ignored person with landmarks: the target mask is the filled landmark polygon (on
// Penn-Fudan it covers the instance mask with IoU 0.986). Augmentation: box jitter, mirroring, brightness
// and contrast. Throws ProcessingError when there is nothing to train on.
BodyMaskNet train_body_mask_net(const LandmarkDataset& data, const MaskNetTrainOptions& options);

// The pixels of `box` resampled to `size` (area averaging), pixels outside the image replicated from its
// border. Shared by training and fitting so that both see the same crops.
cv::Mat crop_box(const cv::Mat& image, const Box& box, cv::Size size);

}  // namespace bodyrec
