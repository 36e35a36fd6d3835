// Runs the mask network's U-Net (mask_net.cc) for fitting, with oneDNN's JIT convolutions on the CPU.
// dlib trains the network; its forward pass, and OpenCV's DNN module which ran it before, are several times
// slower on these small layers (Penn-Fudan, 24x72, one crop: OpenCV 0.7 ms, this 0.2 ms; docs/benchmarks.md).
// The layout is fixed: three levels (two 3x3 convolutions + ReLU each, 2x2 max pooling between them), a
// bottom block, three decoder levels (bilinear 2x upsampling with aligned corners as dlib's, concatenation
// [skip, upsampled], two 3x3 convolutions + ReLU), and a 1x1 convolution to one logit per pixel.
#pragma once

#include <memory>
#include <vector>

#include <opencv2/core/mat.hpp>

namespace bodyrec {

// One convolution: weights in OIHW order (filters x inputs x size x size), batch normalisation folded in.
struct ConvWeights {
  int filters = 0, inputs = 0, size = 0;
  std::vector<float> weights, biases;
};

// Not thread-safe (it keeps its buffers between calls): one per thread. Each call runs on the calling
// thread only, so that several runners can run side by side.
class UnetRunner {
 public:
  // `convs`: the 15 convolutions from the input to the output. `input`: the crops' size (multiples of 8).
  // Throws std::invalid_argument when the convolutions do not make the layout above.
  UnetRunner(const std::vector<ConvWeights>& convs, cv::Size input);
  ~UnetRunner();
  UnetRunner(const UnetRunner&) = delete;
  UnetRunner& operator=(const UnetRunner&) = delete;

  // `crop`: CV_8UC3 BGR of the input size; dlib's input_rgb_image normalisation ((v - mean) / 256, RGB).
  // Returns the logits, input size, CV_32F.
  cv::Mat forward(const cv::Mat& crop);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace bodyrec
