#include "bodyrec/landmarks/dnnl_con.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

namespace bodyrec {
namespace {

// What a dlib layer sees of the layers below it.
struct Below {
  dlib::resizable_tensor output, gradient;
  const dlib::tensor& get_output() const { return output; }
  dlib::tensor& get_gradient_input() { return gradient; }
};

void fill(dlib::tensor& t, dlib::rand& rnd) {
  for (float& v : t) v = static_cast<float>(rnd.get_random_gaussian());
}

// Largest difference relative to the largest magnitude of `want`.
double relative_difference(const dlib::tensor& got, const dlib::tensor& want) {
  EXPECT_EQ(got.size(), want.size());
  double diff = 0, scale = 1e-12;
  for (size_t i = 0; i < want.size() && i < got.size(); ++i) {
    diff = std::max(diff, static_cast<double>(std::abs(got.host()[i] - want.host()[i])));
    scale = std::max(scale, static_cast<double>(std::abs(want.host()[i])));
  }
  return diff / scale;
}

// The layer against dlib's own convolution of the same shape: the same initial weights, output, parameter
// gradient, and input gradient added to what the input's gradient held.
template <long F, long K>
void expect_as_dlib(long samples, long channels, long rows, long cols) {
  dlib::rand rnd(7);
  Below below;
  below.output.set_size(samples, channels, rows, cols);
  fill(below.output, rnd);
  std::srand(3);
  dlib::con_<F, K, K, 1, 1> theirs;
  theirs.setup(below);
  std::srand(3);
  dnnl_con_<F, K> ours;
  ours.setup(below);
  ASSERT_EQ(relative_difference(ours.get_layer_params(), theirs.get_layer_params()), 0.0);
  fill(ours.get_layer_params(), rnd);  // biases too (they start at zero)
  std::copy(ours.get_layer_params().begin(), ours.get_layer_params().end(), theirs.get_layer_params().begin());

  dlib::resizable_tensor out_ours, out_theirs;
  ours.forward(below, out_ours);
  theirs.forward(below, out_theirs);
  ASSERT_EQ(out_ours.num_samples(), samples);
  ASSERT_EQ(out_ours.k(), F);
  ASSERT_EQ(out_ours.nr(), rows);
  ASSERT_EQ(out_ours.nc(), cols);
  EXPECT_LT(relative_difference(out_ours, out_theirs), 1e-5);

  dlib::resizable_tensor gradient_input;
  gradient_input.copy_size(out_theirs);
  fill(gradient_input, rnd);
  Below below_theirs = below;
  below.gradient.copy_size(below.output);
  fill(below.gradient, rnd);
  below_theirs.gradient = below.gradient;
  dlib::resizable_tensor params_ours, params_theirs;
  params_ours.copy_size(ours.get_layer_params());
  params_theirs.copy_size(ours.get_layer_params());
  ours.backward(gradient_input, below, params_ours);
  theirs.backward(gradient_input, below_theirs, params_theirs);
  EXPECT_LT(relative_difference(params_ours, params_theirs), 1e-5);
  EXPECT_LT(relative_difference(below.gradient, below_theirs.gradient), 1e-5);

  // It converts to dlib's layer with the same parameters (how a trained network is saved).
  const dlib::con_<F, K, K, 1, 1> converted = ours;
  EXPECT_EQ(relative_difference(converted.get_layer_params(), ours.get_layer_params()), 0.0);
}

TEST(DnnlConvolution, ComputesWhatDlibsConvolutionDoes) {
  expect_as_dlib<8, 3>(2, 3, 12, 7);
  expect_as_dlib<16, 3>(3, 8, 9, 5);
  expect_as_dlib<1, 1>(2, 8, 6, 4);
}

// Training runs mini-batches, fitting single crops: each input shape gets its own primitives.
TEST(DnnlConvolution, RunsAnotherShapeAfterTheFirst) {
  dlib::rand rnd(1);
  Below below;
  below.output.set_size(2, 2, 8, 8);
  fill(below.output, rnd);
  dnnl_con_<4, 3> layer;
  layer.setup(below);
  dlib::resizable_tensor out;
  layer.forward(below, out);
  below.output.set_size(1, 2, 5, 3);
  fill(below.output, rnd);
  layer.forward(below, out);
  EXPECT_EQ(out.num_samples(), 1);
  EXPECT_EQ(out.nr(), 5);
  EXPECT_EQ(out.nc(), 3);
  dlib::con_<4, 3, 3, 1, 1> theirs = layer;
  dlib::resizable_tensor want;
  theirs.forward(below, want);
  EXPECT_LT(relative_difference(out, want), 1e-5);
}

TEST(DnnlConvolution, RejectsParametersOfAnotherShape) {
  DnnlConvolution conv(4, 3);
  dlib::resizable_tensor input(1, 2, 5, 5), params(4 * 3 * 9 + 4), output;
  EXPECT_THROW(conv.forward(input, params, output), std::invalid_argument);
}

}  // namespace
}  // namespace bodyrec
