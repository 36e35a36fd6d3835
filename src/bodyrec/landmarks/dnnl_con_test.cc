#include "bodyrec/landmarks/dnnl_con.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <thread>

#include <omp.h>

#include <gtest/gtest.h>

#include "test_support.h"

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
  // Filled with garbage: the parameters' gradient is written, not added to.
  dlib::resizable_tensor params_ours, params_theirs;
  params_ours.copy_size(ours.get_layer_params());
  params_ours = std::numeric_limits<float>::infinity();
  params_theirs.copy_size(ours.get_layer_params());
  ours.backward(gradient_input, below, params_ours);
  theirs.backward(gradient_input, below_theirs, params_theirs);
  EXPECT_LT(relative_difference(params_ours, params_theirs), 1e-5);
  EXPECT_LT(relative_difference(below.gradient, below_theirs.gradient), 1e-5);

  // It converts to dlib's layer with the same parameters (how a trained network is saved).
  const dlib::con_<F, K, K, 1, 1> converted = ours;
  EXPECT_EQ(relative_difference(converted.get_layer_params(), ours.get_layer_params()), 0.0);
}

// The mask network's layers (mask_net.cc) at the 24x72 input's sizes, and a few others.
TEST(DnnlConvolution, ComputesWhatDlibsConvolutionDoes) {
  expect_as_dlib<8, 3>(2, 3, 12, 7);
  expect_as_dlib<16, 3>(3, 8, 9, 5);
  expect_as_dlib<1, 1>(2, 8, 6, 4);
  expect_as_dlib<8, 3>(2, 8, 72, 24);
  expect_as_dlib<8, 3>(2, 16, 72, 24);
  expect_as_dlib<8, 3>(2, 32, 36, 12);
  expect_as_dlib<16, 3>(2, 16, 36, 12);
  expect_as_dlib<32, 3>(2, 32, 9, 3);
  expect_as_dlib<16, 3>(2, 64, 18, 6);
}

// dlib's own check of a layer: finite differences of its outputs against its gradients.
TEST(DnnlConvolution, PassesDlibsLayerTest) {
  const dlib::layer_test_results result = dlib::test_layer(dnnl_con_<4, 3>());
  EXPECT_TRUE(result.was_good) << result.log;
}

// The solver updates the layer as dlib's Adam updates dlib::con_: with weight decay, not the biases.
TEST(DnnlConvolution, AdamUpdatesItAsDlibsConvolution) {
  dlib::rand rnd(5);
  Below below;
  below.output.set_size(1, 2, 5, 5);
  fill(below.output, rnd);
  std::srand(3);
  dnnl_con_<3, 3> ours;
  ours.setup(below);
  fill(ours.get_layer_params(), rnd);
  dlib::con_<3, 3, 3, 1, 1> theirs = ours;
  dlib::resizable_tensor gradient;
  gradient.copy_size(ours.get_layer_params());
  fill(gradient, rnd);
  ConAwareAdam for_ours(0.1f, 0.9f, 0.999f);
  dlib::adam for_theirs(0.1f, 0.9f, 0.999f);
  const dlib::tensor& step_ours = for_ours(0.01f, ours, gradient);
  const dlib::tensor& step_theirs = for_theirs(0.01f, theirs, gradient);
  EXPECT_EQ(relative_difference(step_ours, step_theirs), 0.0);
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

// Two networks train side by side, one thread each: the layer must start no OpenMP team of its own,
// whatever the calling thread's setting (a new thread has its own pool: a team would add threads).
TEST(DnnlConvolution, StartsNoOpenMpThreads) {
  size_t before = 0, after = 0;
  std::thread trainer([&] {
    omp_set_num_threads(4);
    before = testing::process_threads();
    dlib::rand rnd(2);
    Below below;
    below.output.set_size(2, 8, 16, 8);
    fill(below.output, rnd);
    below.gradient.copy_size(below.output);
    below.gradient = 0;
    dnnl_con_<8, 3> layer;
    layer.setup(below);
    dlib::resizable_tensor out, params_grad;
    layer.forward(below, out);
    params_grad.copy_size(layer.get_layer_params());
    layer.backward(out, below, params_grad);
    after = testing::process_threads();
  });
  trainer.join();
  EXPECT_GT(before, 0u);
  EXPECT_LE(after, before);
}

TEST(DnnlConvolution, RejectsParametersOfAnotherShape) {
  DnnlConvolution conv(4, 3);
  dlib::resizable_tensor input(1, 2, 5, 5), params(4 * 3 * 9 + 4), output;
  EXPECT_THROW(conv.forward(input, params, output), std::invalid_argument);
}

}  // namespace
}  // namespace bodyrec
