#include "bodyrec/landmarks/dnnl_con.h"

#include <array>
#include <map>
#include <stdexcept>
#include <vector>

#include <oneapi/dnnl/dnnl.hpp>

#include "bodyrec/landmarks/one_omp_thread.h"

namespace bodyrec {
namespace {

using dnnl::memory;
using Shape = std::array<long, 4>;  // n, c, h, w of the input

// oneDNN's memory objects take non-const pointers; the tensors passed through this are only read.
float* data(const dlib::tensor& t) { return const_cast<float*>(t.host()); }

}  // namespace

struct DnnlConvolution::Impl {
  long filters, size;
  dnnl::engine engine{dnnl::engine::kind::cpu, 0};
  dnnl::stream stream{engine};

  // A tensor in dlib's layout (NCHW, OIHW) and, when the primitives want another layout (the fast direct
  // convolutions want blocked ones), a buffer in theirs.
  struct Operand {
    memory::desc user, wanted;
    memory buffer;  // empty when wanted == user
    Operand() = default;
    Operand(const memory::desc& u, const memory::desc& w, const dnnl::engine& e) : user(u), wanted(w) {
      if (wanted != user) buffer = memory(wanted, e);
    }
    // The primitive's argument for the dlib tensor at `p`, copied in when `in`.
    memory use(float* p, bool in, const dnnl::engine& e, const dnnl::stream& s) {
      memory given(user, e, p);
      if (!buffer) return given;
      if (in) dnnl::reorder(given, buffer).execute(s, given, buffer);
      return buffer;
    }
    // Copies a result out to the dlib tensor at `p` (nothing to do when the primitive wrote it there).
    void out(float* p, const dnnl::engine& e, const dnnl::stream& s) {
      if (!buffer) return;
      memory given(user, e, p);
      dnnl::reorder(buffer, given).execute(s, buffer, given);
    }
  };

  // The primitives for one input shape, made on first use.
  struct Primitives {
    memory::desc bias;
    Operand src, weights, dst;                          // forward
    Operand bwd_src, diff_dst_w, diff_weights;          // backward weights
    Operand bwd_weights, diff_dst_d, diff_src;          // backward data
    dnnl::convolution_forward forward;
    dnnl::convolution_backward_data backward_data;
    dnnl::convolution_backward_weights backward_weights;
    std::vector<float> input_grad;  // backward_data's result, then added to dlib's gradient
  };
  std::map<Shape, Primitives> made;

  Primitives& primitives(const dlib::tensor& input) {
    const Shape shape{input.num_samples(), input.k(), input.nr(), input.nc()};
    auto found = made.find(shape);
    if (found != made.end()) return found->second;
    const memory::dim n = shape[0], c = shape[1], h = shape[2], w = shape[3], k = size, pad = size / 2;
    using tag = memory::format_tag;
    const auto f32 = memory::data_type::f32;
    const memory::desc src({n, c, h, w}, f32, tag::nchw), dst({n, filters, h, w}, f32, tag::nchw),
        weights({filters, c, k, k}, f32, tag::oihw);
    const memory::desc src_any({n, c, h, w}, f32, tag::any), dst_any({n, filters, h, w}, f32, tag::any),
        weights_any({filters, c, k, k}, f32, tag::any);
    Primitives p;
    p.bias = memory::desc({filters}, f32, tag::x);
    const memory::dims stride{1, 1}, padding{pad, pad};
    const dnnl::convolution_forward::primitive_desc forward(
        dnnl::convolution_forward::desc(dnnl::prop_kind::forward_training, dnnl::algorithm::convolution_direct,
                                        src_any, weights_any, p.bias, dst_any, stride, padding, padding),
        engine);
    p.forward = dnnl::convolution_forward(forward);
    p.src = Operand(src, forward.src_desc(), engine);
    p.weights = Operand(weights, forward.weights_desc(), engine);
    p.dst = Operand(dst, forward.dst_desc(), engine);
    const dnnl::convolution_backward_data::primitive_desc backward_data(
        dnnl::convolution_backward_data::desc(dnnl::algorithm::convolution_direct, src_any, weights_any, dst_any,
                                              stride, padding, padding),
        engine, forward);
    p.backward_data = dnnl::convolution_backward_data(backward_data);
    p.bwd_weights = Operand(weights, backward_data.weights_desc(), engine);
    p.diff_dst_d = Operand(dst, backward_data.diff_dst_desc(), engine);
    p.diff_src = Operand(src, backward_data.diff_src_desc(), engine);
    const dnnl::convolution_backward_weights::primitive_desc backward_weights(
        dnnl::convolution_backward_weights::desc(dnnl::algorithm::convolution_direct, src_any, weights_any, p.bias,
                                                 dst_any, stride, padding, padding),
        engine, forward);
    p.backward_weights = dnnl::convolution_backward_weights(backward_weights);
    p.bwd_src = Operand(src, backward_weights.src_desc(), engine);
    p.diff_dst_w = Operand(dst, backward_weights.diff_dst_desc(), engine);
    p.diff_weights = Operand(weights, backward_weights.diff_weights_desc(), engine);
    p.input_grad.resize(static_cast<size_t>(n * c * h * w));
    return made.emplace(shape, std::move(p)).first->second;
  }

  void check(const dlib::tensor& input, const dlib::tensor& params) const {
    if (params.size() != static_cast<size_t>(filters * input.k() * size * size + filters))
      throw std::invalid_argument("DnnlConvolution: " + std::to_string(params.size()) + " parameters for " +
                                  std::to_string(input.k()) + " input channels");
  }
  void check_gradients(const dlib::tensor& output_grad, const dlib::tensor& input, const dlib::tensor& params,
                       const dlib::tensor& input_grad, const dlib::tensor& params_grad) const {
    check(input, params);
    if (output_grad.num_samples() != input.num_samples() || output_grad.k() != filters ||
        output_grad.nr() != input.nr() || output_grad.nc() != input.nc() || input_grad.size() != input.size() ||
        params_grad.size() != params.size())
      throw std::invalid_argument("DnnlConvolution: gradients of other shapes than the input, output and parameters");
  }
};

DnnlConvolution::DnnlConvolution(long filters, long size) : impl_(std::make_unique<Impl>()) {
  impl_->filters = filters;
  impl_->size = size;
}

DnnlConvolution::~DnnlConvolution() = default;

void DnnlConvolution::forward(const dlib::tensor& input, const dlib::tensor& params, dlib::resizable_tensor& output) {
  Impl& m = *impl_;
  m.check(input, params);
  const OneOmpThread one_thread;
  Impl::Primitives& p = m.primitives(input);
  output.set_size(input.num_samples(), m.filters, input.nr(), input.nc());
  float* weights = data(params);
  const size_t weight_count = p.weights.user.get_size() / sizeof(float);
  p.forward.execute(m.stream, {{DNNL_ARG_SRC, p.src.use(data(input), true, m.engine, m.stream)},
                               {DNNL_ARG_WEIGHTS, p.weights.use(weights, true, m.engine, m.stream)},
                               {DNNL_ARG_BIAS, memory(p.bias, m.engine, weights + weight_count)},
                               {DNNL_ARG_DST, p.dst.use(output.host(), false, m.engine, m.stream)}});
  p.dst.out(output.host(), m.engine, m.stream);
  m.stream.wait();
}

void DnnlConvolution::backward(const dlib::tensor& output_grad, const dlib::tensor& input, const dlib::tensor& params,
                               dlib::tensor& input_grad, dlib::tensor& params_grad) {
  Impl& m = *impl_;
  m.check_gradients(output_grad, input, params, input_grad, params_grad);
  const OneOmpThread one_thread;
  Impl::Primitives& p = m.primitives(input);
  const size_t weight_count = p.weights.user.get_size() / sizeof(float);
  float* grad = params_grad.host();
  const auto in = [&](Impl::Operand& o, const dlib::tensor& t) { return o.use(data(t), true, m.engine, m.stream); };
  // Both passes read the output's gradient: copied once when they want it in the same layout.
  const memory diff_dst = in(p.diff_dst_w, output_grad);
  const bool same_layout = p.diff_dst_d.wanted == p.diff_dst_w.wanted;
  p.backward_weights.execute(m.stream, {{DNNL_ARG_SRC, in(p.bwd_src, input)},
                                        {DNNL_ARG_DIFF_DST, diff_dst},
                                        {DNNL_ARG_DIFF_WEIGHTS, p.diff_weights.use(grad, false, m.engine, m.stream)},
                                        {DNNL_ARG_DIFF_BIAS, memory(p.bias, m.engine, grad + weight_count)}});
  p.diff_weights.out(grad, m.engine, m.stream);
  p.backward_data.execute(m.stream, {{DNNL_ARG_DIFF_DST, same_layout ? diff_dst : in(p.diff_dst_d, output_grad)},
                                     {DNNL_ARG_WEIGHTS, in(p.bwd_weights, params)},
                                     {DNNL_ARG_DIFF_SRC, p.diff_src.use(p.input_grad.data(), false, m.engine, m.stream)}});
  p.diff_src.out(p.input_grad.data(), m.engine, m.stream);
  m.stream.wait();
  float* sum = input_grad.host();
  for (size_t i = 0; i < p.input_grad.size(); ++i) sum[i] += p.input_grad[i];
}

}  // namespace bodyrec
