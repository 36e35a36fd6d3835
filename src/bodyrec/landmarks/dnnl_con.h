// A dlib layer that trains a convolution with oneDNN: dlib's own CPU convolution (img2col, a matrix
// product, col2img per sample) was most of the mask network's training time (docs/benchmarks.md). The
// layer keeps its weights in a dlib::con_ of the same shape (same parameters, same initial weights drawn
// from std::rand(), same layout: filters then biases) and converts to it, so a network trained with it
// copies into one made of dlib::con_ layers (mask_net.cc's RunNet) and saves as dlib would.
// Square filters, stride 1, padding size / 2 (dlib::con_'s defaults). One thread per call (OneOmpThread).
// Train with ConAwareAdam below: dlib's own Adam would not know the layer and decay its biases too.
#pragma once

#include <iosfwd>
#include <memory>

#include <dlib/dnn.h>

namespace bodyrec {

// The oneDNN side, per input shape; not thread-safe (one per layer copy).
class DnnlConvolution {
 public:
  DnnlConvolution(long filters, long size);
  ~DnnlConvolution();
  DnnlConvolution(const DnnlConvolution&) = delete;
  DnnlConvolution& operator=(const DnnlConvolution&) = delete;

  // `params`: filters x inputs x size x size weights (OIHW), then `filters` biases. NCHW activations.
  void forward(const dlib::tensor& input, const dlib::tensor& params, dlib::resizable_tensor& output);
  // Writes the parameters' gradient to `params_grad` and adds the input's to `input_grad` (dlib's contract).
  void backward(const dlib::tensor& output_grad, const dlib::tensor& input, const dlib::tensor& params,
                dlib::tensor& input_grad, dlib::tensor& params_grad);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

template <long F, long K>
class dnnl_con_ {
 public:
  using dlib_layer = dlib::con_<F, K, K, 1, 1>;
  static_assert(K % 2 == 1, "odd filter sizes: padding K / 2 keeps the size");

  dnnl_con_() = default;
  dnnl_con_(const dnnl_con_& other) : layer_(other.layer_) {}  // a copy makes its own primitives
  dnnl_con_& operator=(const dnnl_con_& other) {
    layer_ = other.layer_;
    conv_.reset();
    return *this;
  }
  operator dlib_layer() const { return layer_; }
  const dlib_layer& layer() const { return layer_; }
  void clean() { conv_.reset(); }  // dlib's net.clean(): the primitives and their buffers go

  template <typename SUBNET>
  void setup(const SUBNET& sub) { layer_.setup(sub); }
  template <typename SUBNET>
  void forward(const SUBNET& sub, dlib::resizable_tensor& output) {
    convolution().forward(sub.get_output(), layer_.get_layer_params(), output);
  }
  template <typename SUBNET>
  void backward(const dlib::tensor& gradient_input, SUBNET& sub, dlib::tensor& params_grad) {
    convolution().backward(gradient_input, sub.get_output(), layer_.get_layer_params(), sub.get_gradient_input(),
                           params_grad);
  }
  const dlib::tensor& get_layer_params() const { return layer_.get_layer_params(); }
  dlib::tensor& get_layer_params() { return layer_.get_layer_params(); }
  dlib::dpoint map_input_to_output(dlib::dpoint p) const { return layer_.map_input_to_output(p); }
  dlib::dpoint map_output_to_input(dlib::dpoint p) const { return layer_.map_output_to_input(p); }

  friend void serialize(const dnnl_con_& item, std::ostream& out) { serialize(item.layer_, out); }
  friend void deserialize(dnnl_con_& item, std::istream& in) {
    deserialize(item.layer_, in);
    item.conv_.reset();
  }
  friend std::ostream& operator<<(std::ostream& out, const dnnl_con_& item) { return out << "dnnl_" << item.layer_; }
  friend void to_xml(const dnnl_con_& item, std::ostream& out) { to_xml(item.layer_, out); }

 private:
  DnnlConvolution& convolution() {
    if (!conv_) conv_ = std::make_unique<DnnlConvolution>(F, K);
    return *conv_;
  }
  dlib_layer layer_;
  std::unique_ptr<DnnlConvolution> conv_;
};

template <long F, long K, typename SUBNET>
using dnnl_con = dlib::add_layer<dnnl_con_<F, K>, SUBNET>;

// dlib's Adam, updating a dnnl_con_ exactly as it updates the dlib::con_ inside it (weight decay and the
// learning-rate multipliers as dlib::con_ sets them: none on the biases' decay).
class ConAwareAdam : public dlib::adam {
 public:
  using dlib::adam::adam;
  using dlib::adam::operator();
  template <long F, long K>
  const dlib::tensor& operator()(const float learning_rate, const dnnl_con_<F, K>& l, const dlib::tensor& params_grad) {
    return dlib::adam::operator()(learning_rate, l.layer(), params_grad);
  }
};

}  // namespace bodyrec
