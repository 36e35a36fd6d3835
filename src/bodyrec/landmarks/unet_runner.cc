#include "bodyrec/landmarks/unet_runner.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <functional>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include <oneapi/dnnl/dnnl.hpp>

#include "bodyrec/landmarks/one_omp_thread.h"

namespace bodyrec {
namespace {

using dnnl::memory;

// Activations in channels-last order (NHWC, batch 1): the upsampling and concatenation below are plain
// loops over pixels, and oneDNN's convolutions run as fast on this layout as on its blocked ones.
struct Tensor {
  int c, h, w;
  std::vector<float> data;
  Tensor(int channels, int rows, int cols) : c(channels), h(rows), w(cols), data(static_cast<size_t>(c) * h * w) {}
  float* pixel(int y, int x) { return data.data() + (static_cast<size_t>(y) * w + x) * c; }
  memory::desc desc() const { return memory::desc({1, c, h, w}, memory::data_type::f32, memory::format_tag::nhwc); }
};

// out = [skip, `below` upsampled to skip's size] along the channels. The upsampling is dlib's
// resize_bilinear (corners aligned), float for float; oneDNN 2.6's resampling has no corner-aligned mode.
// Each row of `below` is interpolated across once into `across` (every output row blends two of them),
// the same products and sums in the same order as interpolating each output pixel from its four
// neighbours, for half the work.
class Join {
 public:
  Join(Tensor& skip, Tensor& below, Tensor& out)
      : skip_(skip), below_(below), out_(out), across_(static_cast<size_t>(below.h) * out.w * below.c) {
    const auto place = [](int from, int to, std::vector<Tap>& taps) {
      const float scale = (from - 1) / static_cast<float>(std::max(to - 1, 1));
      for (int i = 0; i < to; ++i) {
        const float f = i * scale;
        const int low = static_cast<int>(std::floor(f));
        taps.push_back({low, std::min(low + 1, from - 1), f - low});
      }
    };
    place(below.w, out.w, columns_);
    place(below.h, out.h, rows_);
  }

  void operator()() {
    const int c = below_.c;
    for (int r = 0; r < below_.h; ++r) {
      float* a = &across_[static_cast<size_t>(r) * out_.w * c];
      for (int x = 0; x < out_.w; ++x, a += c) {
        const Tap& t = columns_[static_cast<size_t>(x)];
        const float *left = below_.pixel(r, t.low), *right = below_.pixel(r, t.high);
        for (int k = 0; k < c; ++k) a[k] = (1 - t.weight) * left[k] + t.weight * right[k];
      }
    }
    for (int y = 0; y < out_.h; ++y) {
      const Tap& t = rows_[static_cast<size_t>(y)];
      const float* top = &across_[static_cast<size_t>(t.low) * out_.w * c];
      const float* bottom = &across_[static_cast<size_t>(t.high) * out_.w * c];
      for (int x = 0; x < out_.w; ++x, top += c, bottom += c) {
        float* o = out_.pixel(y, x);
        std::copy_n(skip_.pixel(y, x), skip_.c, o);
        o += skip_.c;
        for (int k = 0; k < c; ++k) o[k] = (1 - t.weight) * top[k] + t.weight * bottom[k];
      }
    }
  }

 private:
  struct Tap {
    int low, high;  // the two source rows or columns
    float weight;   // of `high`
  };
  Tensor &skip_, &below_, &out_;
  std::vector<float> across_;  // below.h x out.w x below.c
  std::vector<Tap> columns_, rows_;
};

}  // namespace

struct UnetRunner::Impl {
  dnnl::engine engine{dnnl::engine::kind::cpu, 0};
  dnnl::stream stream{engine};
  std::deque<Tensor> tensors;  // stable addresses
  std::vector<std::function<void()>> steps;

  Tensor& make(int c, int h, int w) {
    tensors.emplace_back(c, h, w);
    return tensors.back();
  }
  memory wrap(Tensor& t) { return memory(t.desc(), engine, t.data.data()); }
  void run(dnnl::primitive prim, std::unordered_map<int, memory> args) {
    steps.push_back([this, prim, args] { prim.execute(stream, args); });
  }

  Tensor& conv(const ConvWeights& cw, Tensor& src, bool relu) {
    if (cw.inputs != src.c || cw.weights.size() != static_cast<size_t>(cw.filters) * cw.inputs * cw.size * cw.size ||
        cw.biases.size() != static_cast<size_t>(cw.filters) || cw.size % 2 == 0)
      throw std::invalid_argument("UnetRunner: convolution of " + std::to_string(cw.inputs) + " inputs after " +
                                  std::to_string(src.c) + " channels, or malformed weights");
    Tensor& dst = make(cw.filters, src.h, src.w);
    const memory::dim k = cw.size, pad = cw.size / 2;
    const memory::desc weights_any({cw.filters, cw.inputs, k, k}, memory::data_type::f32, memory::format_tag::any);
    const memory::desc bias_desc({cw.filters}, memory::data_type::f32, memory::format_tag::x);
    const dnnl::convolution_forward::desc d(dnnl::prop_kind::forward_inference, dnnl::algorithm::convolution_direct,
                                            src.desc(), weights_any, bias_desc, dst.desc(), {1, 1}, {pad, pad},
                                            {pad, pad});
    dnnl::primitive_attr attr;
    if (relu) {
      dnnl::post_ops ops;
      ops.append_eltwise(1.f, dnnl::algorithm::eltwise_relu, 0.f, 0.f);
      attr.set_post_ops(ops);
    }
    const dnnl::convolution_forward::primitive_desc pd(d, attr, engine);
    // The weights in the layout the chosen implementation wants, once.
    std::vector<float> oihw = cw.weights;
    memory given({{cw.filters, cw.inputs, k, k}, memory::data_type::f32, memory::format_tag::oihw}, engine, oihw.data());
    memory weights(pd.weights_desc(), engine);
    dnnl::reorder(given, weights).execute(stream, given, weights);
    stream.wait();
    memory bias(bias_desc, engine);
    std::copy(cw.biases.begin(), cw.biases.end(), static_cast<float*>(bias.get_data_handle()));
    run(dnnl::convolution_forward(pd),
        {{DNNL_ARG_SRC, wrap(src)}, {DNNL_ARG_WEIGHTS, weights}, {DNNL_ARG_BIAS, bias}, {DNNL_ARG_DST, wrap(dst)}});
    return dst;
  }

  Tensor& pool(Tensor& src) {  // 2x2 max, stride 2
    Tensor& dst = make(src.c, src.h / 2, src.w / 2);
    const dnnl::pooling_forward::desc d(dnnl::prop_kind::forward_inference, dnnl::algorithm::pooling_max, src.desc(),
                                        dst.desc(), {2, 2}, {2, 2}, {0, 0}, {0, 0});
    run(dnnl::pooling_forward(dnnl::pooling_forward::primitive_desc(d, engine)),
        {{DNNL_ARG_SRC, wrap(src)}, {DNNL_ARG_DST, wrap(dst)}});
    return dst;
  }

  Tensor& joined(Tensor& skip, Tensor& below) {
    Tensor& dst = make(skip.c + below.c, skip.h, skip.w);
    steps.push_back(Join(skip, below, dst));
    return dst;
  }
};

UnetRunner::UnetRunner(const std::vector<ConvWeights>& convs, cv::Size input) : impl_(std::make_unique<Impl>()) {
  if (convs.size() != 15) throw std::invalid_argument("UnetRunner: 15 convolutions expected");
  if (input.width < 8 || input.height < 8 || input.width % 8 || input.height % 8)
    throw std::invalid_argument("UnetRunner: the input size must be multiples of 8");
  const OneOmpThread one_thread;
  Impl& n = *impl_;
  size_t next = 0;
  const auto block = [&](Tensor& in) -> Tensor& {
    Tensor& a = n.conv(convs[next++], in, true);
    return n.conv(convs[next++], a, true);
  };
  Tensor& in = n.make(3, input.height, input.width);
  Tensor& s1 = block(in);
  Tensor& s2 = block(n.pool(s1));
  Tensor& s3 = block(n.pool(s2));
  Tensor& bottom = block(n.pool(s3));
  Tensor& u3 = block(n.joined(s3, bottom));
  Tensor& u2 = block(n.joined(s2, u3));
  Tensor& u1 = block(n.joined(s1, u2));
  n.conv(convs[next++], u1, false);
  if (n.tensors.back().c != 1) throw std::invalid_argument("UnetRunner: the last convolution must give one logit");
}

UnetRunner::~UnetRunner() = default;

cv::Mat UnetRunner::forward(const cv::Mat& crop) {
  static const float mean[3] = {122.782f, 117.001f, 104.298f};
  Impl& n = *impl_;
  Tensor& in = n.tensors.front();
  if (crop.type() != CV_8UC3 || crop.rows != in.h || crop.cols != in.w)
    throw std::invalid_argument("UnetRunner: the crop must be CV_8UC3 of the network's input size");
  for (int y = 0; y < in.h; ++y) {
    const cv::Vec3b* row = crop.ptr<cv::Vec3b>(y);
    for (int x = 0; x < in.w; ++x) {
      float* p = in.pixel(y, x);
      for (int ch = 0; ch < 3; ++ch) p[ch] = (row[x][2 - ch] - mean[ch]) / 256.f;
    }
  }
  const OneOmpThread one_thread;
  for (const auto& step : n.steps) step();
  n.stream.wait();
  Tensor& out = n.tensors.back();
  return cv::Mat(out.h, out.w, CV_32F, out.data.data()).clone();
}

}  // namespace bodyrec
