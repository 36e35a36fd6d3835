#include "bodyrec/landmarks/mask_net.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <istream>
#include <ostream>
#include <random>

#include <dlib/dnn.h>
#include <dlib/opencv/cv_image.h>
#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/landmarks/contour.h"
#include "bodyrec/landmarks/dnnl_con.h"
#include "bodyrec/landmarks/leg_gap.h"
#include "bodyrec/landmarks/unet_runner.h"

namespace bodyrec {
namespace {

// The network: a three-level U-Net, 8 channels at full resolution (doubling twice), two 3x3 convolutions
// per level, skip connections by concatenation, one logit per pixel. About 53 000 weights; ~10 M
// multiply-adds for a 24x72 crop (the default), ~18 M for 32x96.
constexpr int kChannels = 8;
template <long N, long K, typename S> using dlib_con = dlib::con<N, K, K, 1, 1, S>;
template <int N, template <typename> class BN, template <long, long, typename> class CON, typename S>
using block = dlib::relu<BN<CON<N, 3, dlib::relu<BN<CON<N, 3, S>>>>>>;
template <template <typename> class TAGGED, template <typename> class PREV, typename S>
using join = dlib::add_layer<dlib::concat_<TAGGED, PREV>, PREV<dlib::resize_prev_to_tagged<TAGGED, S>>>;
template <typename S> using skip1 = dlib::add_tag_layer<2101, S>;
template <typename S> using skip2 = dlib::add_tag_layer<2102, S>;
template <typename S> using skip3 = dlib::add_tag_layer<2103, S>;
template <typename S> using up1 = dlib::add_tag_layer<2111, S>;
template <typename S> using up2 = dlib::add_tag_layer<2112, S>;
template <typename S> using up3 = dlib::add_tag_layer<2113, S>;
template <template <typename> class BN, template <long, long, typename> class CON>
using unet = CON<1, 1,
    block<kChannels, BN, CON, join<skip1, up1, dlib::upsample<2,
    block<kChannels, BN, CON, join<skip2, up2, dlib::upsample<2,
    block<2 * kChannels, BN, CON, join<skip3, up3, dlib::upsample<2,
    block<4 * kChannels, BN, CON, dlib::max_pool<2, 2, 2, 2,
    skip3<block<4 * kChannels, BN, CON, dlib::max_pool<2, 2, 2, 2,
    skip2<block<2 * kChannels, BN, CON, dlib::max_pool<2, 2, 2, 2,
    skip1<block<kChannels, BN, CON, dlib::input_rgb_image>>>>>>>>>>>>>>>>>>>>;
// Trained with oneDNN's convolutions (dnnl_con.h), saved and checked with dlib's: the same parameters.
using TrainNet = dlib::loss_binary_log_per_pixel<unet<dlib::bn_con, dnnl_con>>;
using RunNet = dlib::loss_binary_log_per_pixel<unet<dlib::affine, dlib_con>>;

// Raw bytes at the start of every model file (before dlib's serialisation), and the format version.
constexpr char kMagic[] = "BODYREC-MASKNET\n";
constexpr size_t kMagicBytes = sizeof(kMagic) - 1;
constexpr int kVersion = 2;  // 2: a count of networks before them (1: one network)

dlib::matrix<dlib::rgb_pixel> to_dlib(const cv::Mat& bgr) {
  dlib::matrix<dlib::rgb_pixel> m;
  dlib::assign_image(m, dlib::cv_image<dlib::bgr_pixel>(bgr));
  return m;
}

// dlib trains the network; UnetRunner (oneDNN) runs it, several times faster on the CPU for these small
// layers. Each batch normalisation (an affine_ after training) is folded into the convolution before it.
// TrainedMaskNet.RunnerRunsTheDlibNetwork checks the outputs agree.
struct CollectWeights {  // visits computational layers from the output back to the input
  std::vector<ConvWeights>* convs;
  std::vector<std::vector<float>>* scales;  // gamma then beta of each affine_
  template <long F, long R, long C, int SY, int SX, int PY, int PX>
  void operator()(const dlib::con_<F, R, C, SY, SX, PY, PX>& layer) const {
    static_assert(R == C && SY == 1 && SX == 1, "square filters, stride 1");
    const dlib::tensor& p = layer.get_layer_params();
    ConvWeights c;
    c.filters = static_cast<int>(F);
    c.size = static_cast<int>(R);
    c.inputs = static_cast<int>((p.size() - F) / (F * R * C));
    const float* d = p.host();
    const size_t n = static_cast<size_t>(F * c.inputs * R * C);
    c.weights.assign(d, d + n);
    c.biases.assign(d + n, d + p.size());
    convs->push_back(std::move(c));
  }
  void operator()(const dlib::affine_& layer) const {
    const dlib::matrix<float> gamma = dlib::mat(layer.get_gamma()), beta = dlib::mat(layer.get_beta());
    std::vector<float> v(gamma.begin(), gamma.end());
    v.insert(v.end(), beta.begin(), beta.end());
    scales->push_back(std::move(v));
  }
  template <typename T>
  void operator()(const T&) const {}
};

// The trained network's 15 convolutions from the input to the output, batch normalisations folded in.
std::vector<ConvWeights> folded_convs(RunNet& trained) {
  std::vector<ConvWeights> convs;
  std::vector<std::vector<float>> scales;
  dlib::visit_computational_layers(trained, CollectWeights{&convs, &scales});
  std::reverse(convs.begin(), convs.end());
  std::reverse(scales.begin(), scales.end());
  CV_Assert(convs.size() == 15 && scales.size() == 14);
  for (size_t i = 0; i < scales.size(); ++i) {  // fold: gamma * (w x + b) + beta
    ConvWeights& c = convs[i];
    const std::vector<float>& s = scales[i];
    const size_t per_filter = c.weights.size() / static_cast<size_t>(c.filters);
    for (size_t f = 0; f < static_cast<size_t>(c.filters); ++f) {
      for (size_t k = 0; k < per_filter; ++k) c.weights[f * per_filter + k] *= s[f];
      c.biases[f] = c.biases[f] * s[f] + s[static_cast<size_t>(c.filters) + f];
    }
  }
  return convs;
}

struct PixelBox {  // a box rounded to whole pixels, at least 1x1
  int x, y, width, height;
  explicit PixelBox(const Box& b)
      : x(static_cast<int>(std::lround(b.x))), y(static_cast<int>(std::lround(b.y))),
        width(std::max(1, static_cast<int>(std::lround(b.width)))),
        height(std::max(1, static_cast<int>(std::lround(b.height)))) {}
};

// Crops fitting passes at once (the box and its mirror image).
constexpr size_t kMaxCrops = 2;

struct Member {
  Member() = default;
  Member(Member&&) = default;  // not copyable (so that vectors of them move)
  Member& operator=(Member&&) = default;
  mutable RunNet net;  // what is saved (dlib's serialisation); its forward pass keeps buffers
  // What runs (built from `net`), one per crop so that the crops can run side by side: a runner keeps
  // buffers between calls and is not thread-safe.
  std::vector<std::unique_ptr<UnetRunner>> runners;
  void build_runners(cv::Size input) {
    runners.clear();
    const std::vector<ConvWeights> convs = folded_convs(net);
    for (size_t i = 0; i < kMaxCrops; ++i) runners.push_back(std::make_unique<UnetRunner>(convs, input));
  }
};

// Each crop's logits, the mean over the networks. Every (network, crop) pass runs on one thread, side by
// side on OpenCV's threads: one pass of these small layers gains little from being split across threads,
// two passes side by side nearly twice.
std::vector<cv::Mat> mean_forward(const std::vector<Member>& members, const std::vector<cv::Mat>& crops) {
  CV_Assert(!crops.empty() && crops.size() <= kMaxCrops);
  const size_t n = crops.size();
  if (members.size() * n == 1) return {members.front().runners.front()->forward(crops.front())};
  std::vector<cv::Mat> each(members.size() * n);
  cv::parallel_for_(cv::Range(0, static_cast<int>(each.size())), [&](const cv::Range& range) {
    for (size_t i = static_cast<size_t>(range.start); i < static_cast<size_t>(range.end); ++i)
      each[i] = members[i / n].runners[i % n]->forward(crops[i % n]);
  });
  std::vector<cv::Mat> mean(each.begin(), each.begin() + static_cast<std::ptrdiff_t>(n));
  for (size_t i = n; i < each.size(); ++i) mean[i % n] += each[i];
  if (members.size() > 1)
    for (cv::Mat& m : mean) m /= static_cast<double>(members.size());
  return mean;
}

}  // namespace

struct BodyMaskNet::Impl {
  std::vector<Member> members;  // one network, or several whose logits are averaged
  cv::Size input;
  double threshold = 0.5;
  bool mirror_average = true;
  bool leg_slit = true;
};

void MaskNetTrainOptions::check() const {
  const auto fail = [](const char* field, const std::string& problem) {
    throw OptionError("MaskNetTrainOptions", field, problem);
  };
  if (input_width < 8 || input_width % 8 != 0) fail("input_width", "must be a multiple of 8 (e.g. 32)");
  if (input_height < 8 || input_height % 8 != 0) fail("input_height", "must be a multiple of 8 (e.g. 96)");
  if (iterations < 1) fail("iterations", "must be >= 1");
  if (batch < 1) fail("batch", "must be >= 1");
  if (!(learning_rate > 0 && learning_rate < 1)) fail("learning_rate", "must be in (0, 1)");
  if (!(weight_decay >= 0 && weight_decay < 1)) fail("weight_decay", "must be in [0, 1)");
  if (!std::isfinite(threshold)) fail("threshold", "must be a finite logit");
  if (!(box_jitter >= 0 && box_jitter <= 0.5)) fail("box_jitter", "must be in [0, 0.5]");
  if (networks < 1 || networks > kMaxNetworks) fail("networks", "must be in [1, " + std::to_string(kMaxNetworks) + "]");
}

cv::Mat crop_box(const cv::Mat& image, const Box& box, cv::Size size) {
  CV_Assert(!image.empty());
  const PixelBox b(box);
  const cv::Rect inside = cv::Rect(b.x, b.y, b.width, b.height) & cv::Rect(0, 0, image.cols, image.rows);
  cv::Mat region;
  if (inside.area() == 0) {  // wholly outside: the nearest border pixels
    const int cx = std::clamp(b.x + b.width / 2, 0, image.cols - 1), cy = std::clamp(b.y + b.height / 2, 0, image.rows - 1);
    region = cv::Mat(b.height, b.width, image.type());
    region.setTo(cv::Scalar::all(0));
    cv::Mat nearest = image(cv::Rect(cx, cy, 1, 1));
    cv::resize(nearest, region, region.size(), 0, 0, cv::INTER_NEAREST);
  } else {
    cv::copyMakeBorder(image(inside), region, inside.y - b.y, b.y + b.height - inside.y - inside.height,
                       inside.x - b.x, b.x + b.width - inside.x - inside.width, cv::BORDER_REPLICATE);
  }
  cv::Mat out;
  cv::resize(region, out, size, 0, 0, cv::INTER_AREA);
  return out;
}

BodyMaskNet::BodyMaskNet() : impl_(std::make_unique<Impl>()) {}
BodyMaskNet::~BodyMaskNet() = default;
BodyMaskNet::BodyMaskNet(BodyMaskNet&&) noexcept = default;
BodyMaskNet& BodyMaskNet::operator=(BodyMaskNet&&) noexcept = default;

bool BodyMaskNet::recognise(std::istream& in) {
  const auto start = in.tellg();
  char head[kMagicBytes] = {};
  in.read(head, kMagicBytes);
  const bool yes = in.gcount() == static_cast<std::streamsize>(kMagicBytes) && std::memcmp(head, kMagic, kMagicBytes) == 0;
  in.clear();
  in.seekg(start);
  return yes;
}

BodyMaskNet::BodyMaskNet(std::istream& in, const std::string& name) : BodyMaskNet() {
  if (!recognise(in)) throw InputError(name + ": not a bodyrec mask-net model");
  in.ignore(kMagicBytes);
  try {
    int version = 0, width = 0, height = 0, networks = 1;
    dlib::deserialize(version, in);
    if (version < 1 || version > kVersion)
      throw InputError(name + ": mask-net model version " + std::to_string(version) + ", this build reads 1 to " +
                       std::to_string(kVersion));
    dlib::deserialize(width, in);
    dlib::deserialize(height, in);
    dlib::deserialize(impl_->threshold, in);
    if (version >= 2) dlib::deserialize(networks, in);
    if (networks < 1 || networks > kMaxNetworks)
      throw InputError(name + ": mask-net model has " + std::to_string(networks) + " networks (1 to " +
                       std::to_string(kMaxNetworks) + " expected)");
    impl_->members.resize(static_cast<size_t>(networks));
    for (Member& m : impl_->members) dlib::deserialize(m.net, in);
    if (width < 8 || height < 8 || width % 8 || height % 8 || !std::isfinite(impl_->threshold))
      throw InputError(name + ": mask-net model has an invalid input size or threshold");
    impl_->input = cv::Size(width, height);
    for (Member& m : impl_->members) m.build_runners(impl_->input);
  } catch (const dlib::serialization_error& e) {
    std::string why = e.what();
    throw InputError(name + ": truncated or corrupt mask-net model (" + why.substr(0, why.find('\n')) + ")");
  }
}

void BodyMaskNet::save(std::ostream& out) const {
  out.write(kMagic, kMagicBytes);
  dlib::serialize(kVersion, out);
  dlib::serialize(impl_->input.width, out);
  dlib::serialize(impl_->input.height, out);
  dlib::serialize(impl_->threshold, out);
  dlib::serialize(static_cast<int>(impl_->members.size()), out);
  for (const Member& m : impl_->members) dlib::serialize(m.net, out);
}

cv::Size BodyMaskNet::input_size() const { return impl_->input; }
int BodyMaskNet::networks() const { return static_cast<int>(impl_->members.size()); }
double BodyMaskNet::threshold() const { return impl_->threshold; }
void BodyMaskNet::set_threshold(double logit) {
  CV_Assert(std::isfinite(logit));
  impl_->threshold = logit;
}

void BodyMaskNet::set_mirror_average(bool on) { impl_->mirror_average = on; }
bool BodyMaskNet::mirror_average() const { return impl_->mirror_average; }
void BodyMaskNet::set_leg_slit(bool on) { impl_->leg_slit = on; }
bool BodyMaskNet::leg_slit() const { return impl_->leg_slit; }

cv::Mat BodyMaskNet::logits(const cv::Mat& bgr, const Box& box) const {
  CV_Assert(bgr.type() == CV_8UC3);
  return mean_forward(impl_->members, {crop_box(bgr, box, impl_->input)}).front();
}

cv::Mat BodyMaskNet::fitting_logits(const cv::Mat& bgr, const Box& box) const {
  if (!impl_->mirror_average) return logits(bgr, box);
  CV_Assert(bgr.type() == CV_8UC3);
  const cv::Mat crop = crop_box(bgr, box, impl_->input);
  cv::Mat mirrored;
  cv::flip(crop, mirrored, 1);
  // The two crops run side by side (mean_forward).
  std::vector<cv::Mat> out = mean_forward(impl_->members, {crop, mirrored});
  cv::flip(out[1], out[1], 1);
  return 0.5f * (out[0] + out[1]);
}

cv::Mat BodyMaskNet::reference_logits(const cv::Mat& bgr, const Box& box) const {
  CV_Assert(bgr.type() == CV_8UC3);
  const dlib::matrix<dlib::rgb_pixel> crop = to_dlib(crop_box(bgr, box, impl_->input));
  cv::Mat result = cv::Mat::zeros(impl_->input, CV_32F);
  for (const Member& m : impl_->members) {
    const dlib::matrix<float> out = m.net(crop);
    for (int r = 0; r < result.rows; ++r)
      for (int c = 0; c < result.cols; ++c) result.at<float>(r, c) += out(r, c);
  }
  return result / static_cast<double>(impl_->members.size());
}

std::vector<cv::Point2d> BodyMaskNet::fit(const cv::Mat& bgr, const Box& box, int landmarks) const {
  return fit_at(bgr, box, landmarks, {0.0}).front();
}

std::vector<std::vector<cv::Point2d>> BodyMaskNet::fit_at(const cv::Mat& bgr, const Box& box, int landmarks,
                                                          const std::vector<double>& threshold_offsets) const {
  CV_Assert(!threshold_offsets.empty());
  ContourOptions options;
  options.landmarks = landmarks;
  options.min_height = 1;             // the box decides who is a person, not the outline's size
  options.max_border_fraction = 1.0;  // a body fills its box: it always touches the box's sides
  const PixelBox b(box);
  // The outline is traced on the logits upsampled to the box, but at most twice the network's rows tall:
  // finer adds nothing to a mask with that few rows, and tracing a tall box several times would cost more
  // than the network (Penn-Fudan validation, 24x72: the same error, 0.3 ms less per outline).
  const double scale = std::min(1.0, 2.0 * impl_->input.height / b.height);
  const cv::Size size(std::max(1, static_cast<int>(std::lround(b.width * scale))),
                      std::max(1, static_cast<int>(std::lround(b.height * scale))));
  const double sx = static_cast<double>(b.width) / size.width, sy = static_cast<double>(b.height) / size.height;
  // Cubic rather than linear: the dip of the logits between the legs stays deeper (Penn-Fudan validation:
  // 0.05 points less error on two validation models, docs/benchmarks.md).
  cv::Mat up;
  cv::resize(fitting_logits(bgr, box), up, size, 0, 0, cv::INTER_CUBIC);
  double highest = 0;
  cv::minMaxLoc(up, nullptr, &highest);
  // The outlines are independent: traced side by side (OpenCV's threads).
  std::vector<std::vector<cv::Point2d>> outlines(threshold_offsets.size());
  cv::parallel_for_(cv::Range(0, static_cast<int>(threshold_offsets.size())), [&](const cv::Range& range) {
    for (int i = range.start; i < range.end; ++i) {
      // When no pixel passes the threshold, the pixels within 1 of the highest: never an empty mask.
      const double threshold = std::min(impl_->threshold + threshold_offsets[static_cast<size_t>(i)], highest - 1.0);
      cv::Mat mask = up > threshold;
      if (impl_->leg_slit) cut_leg_gap(mask, up, threshold + kLegSlitMargin);
      BodyContour contour = contour_from_mask(mask, options);
      CV_Assert(contour.status == ContourStatus::kOk);
      for (auto& p : contour.points)  // pixel centres back to the box's pixels
        p = cv::Point2d(b.x + (p.x + 0.5) * sx - 0.5, b.y + (p.y + 0.5) * sy - 0.5);
      outlines[static_cast<size_t>(i)] = std::move(contour.points);
    }
  });
  return outlines;
}

BodyMaskNet train_body_mask_net(const LandmarkDataset& data, const MaskNetTrainOptions& options) {
  options.check();
  struct Sample {
    const cv::Mat* image;
    const AnnotatedPerson* person;
  };
  std::vector<Sample> samples;
  for (const auto& image : data.images)
    for (const auto& person : image.people)
      if (!person.ignore && person.landmarks.size() >= 3 && person.box.area() > 0 && !image.image.empty())
        samples.push_back({&image.image, &person});
  if (samples.empty()) throw ProcessingError("no person with landmarks to train the mask network on");

  const cv::Size size(options.input_width, options.input_height);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const double j = options.box_jitter;
  // One mini-batch of augmented crops and their target masks, drawn with `rng`.
  const auto draw = [&](std::mt19937& rng, std::vector<dlib::matrix<dlib::rgb_pixel>>& crops,
                        std::vector<dlib::matrix<float>>& labels) {
    crops.clear();
    labels.clear();
    for (int k = 0; k < options.batch; ++k) {
      const Sample& s = samples[rng() % samples.size()];
      const Box& truth = s.person->box;
      const Box jittered(truth.x + normal(rng) * j * truth.width, truth.y + normal(rng) * j * 2 / 3 * truth.height,
                         truth.width * std::exp(normal(rng) * j * 4 / 3), truth.height * std::exp(normal(rng) * j));
      cv::Mat crop = crop_box(*s.image, jittered, size);
      // Target: the landmark polygon in crop pixels (pixel centres map to pixel centres), 4 fractional bits.
      const PixelBox b(jittered);
      std::vector<cv::Point> polygon;
      for (const auto& p : s.person->landmarks)
        polygon.emplace_back(cvRound(16 * ((p.x - b.x + 0.5) * size.width / b.width - 0.5)),
                             cvRound(16 * ((p.y - b.y + 0.5) * size.height / b.height - 0.5)));
      cv::Mat target = cv::Mat::zeros(size, CV_8U);
      cv::fillPoly(target, std::vector<std::vector<cv::Point>>{polygon}, cv::Scalar(255), cv::LINE_8, 4);
      if (uniform(rng) < 0.5) {
        cv::flip(crop, crop, 1);
        cv::flip(target, target, 1);
      }
      const double contrast = 0.7 + 0.6 * uniform(rng), brightness = (uniform(rng) - 0.5) * 50;
      crop.convertTo(crop, -1, contrast, brightness + 127.5 * (1 - contrast));
      dlib::matrix<float> label(size.height, size.width);
      for (int r = 0; r < size.height; ++r)
        for (int c = 0; c < size.width; ++c) label(r, c) = target.at<uchar>(r, c) ? 1.f : -1.f;
      crops.push_back(to_dlib(crop));
      labels.push_back(std::move(label));
    }
  };

  dlib::matrix<double> schedule(1, options.iterations);
  const int warm_up = std::max(1, options.iterations / 10);
  for (int t = 0; t < options.iterations; ++t) {
    const double f = t < warm_up ? (t + 1.0) / warm_up
                                 : 0.5 * (1 + std::cos(M_PI * (t - warm_up) / std::max(1, options.iterations - warm_up)));
    schedule(0, t) = options.learning_rate * f + 1e-5;
  }
  // Network k draws its crops with seed + k. Each dlib trainer computes on its own thread, so the
  // networks train side by side while this thread draws their crops.
  struct Learner {
    std::mt19937 rng;
    TrainNet net;
    dlib::dnn_trainer<TrainNet, ConAwareAdam> trainer;
    Learner(unsigned seed, float weight_decay)
        : rng(seed), trainer(net, ConAwareAdam(weight_decay, 0.9f, 0.999f)) {}
  };
  std::vector<std::unique_ptr<Learner>> learners;  // the trainers hold references to the networks
  for (int k = 0; k < options.networks; ++k) {
    learners.push_back(std::make_unique<Learner>(options.seed + static_cast<unsigned>(k),
                                                 static_cast<float>(options.weight_decay)));
    learners.back()->trainer.set_mini_batch_size(static_cast<unsigned long>(options.batch));
    learners.back()->trainer.set_learning_rate_schedule(schedule);
  }

  std::vector<dlib::matrix<dlib::rgb_pixel>> crops;
  std::vector<dlib::matrix<float>> labels;
  // dlib sets the layers up on the first step, drawing their initial weights from std::rand(): from the C
  // library's initial state, which a fresh process has, so that a network trained after others in the same
  // process is the one `bodyrec train-shape` makes. The networks are set up one after another (the first
  // step of each waited for), so that each starts from the same weights in every run.
  std::srand(1);
  for (int t = 0; t < options.iterations; ++t) {
    for (size_t k = 0; k < learners.size(); ++k) {
      Learner& l = *learners[k];
      draw(l.rng, crops, labels);
      l.trainer.train_one_step(crops, labels);
      if (t == 0) l.trainer.get_net();  // waits for the trainer's thread
      if (options.verbose && (t + 1) % std::max(1, options.iterations / 10) == 0)
        std::fprintf(stderr, "mask net %zu: iteration %d of %d, loss %.4f\n", k + 1, t + 1, options.iterations,
                     l.trainer.get_average_loss());
    }
  }
  BodyMaskNet model;
  for (const auto& l : learners) {
    l->trainer.get_net();  // waits for the trainer's thread
    l->net.clean();
    Member m;
    m.net = l->net;
    m.build_runners(size);
    model.impl_->members.push_back(std::move(m));
  }
  model.impl_->input = size;
  model.impl_->threshold = options.threshold;
  return model;
}

}  // namespace bodyrec
