#include "bodyrec/reid/xqda.h"

#include <cmath>
#include <tuple>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/reid/cmc.h"
#include "test_support.h"

namespace bodyrec {
namespace {

// Identities differ in 5 "signal" dimensions; every image also has large noise in 45 other dimensions,
// so plain Euclidean distance is mostly noise and a learned metric must find the signal.
struct Synthetic {
  std::vector<std::vector<float>> features;
  std::vector<int> ids, cams;
};

// `signals` identity dimensions, every `spacing`-th one, with camera noise `camera_noise`; the other
// dimensions are noise of deviation `noise`.
struct Layout {
  int dims = 50, signals = 5, spacing = 1;
  double camera_noise = 0.05, noise = 3.0;
};

Synthetic make_data(int identities, uint64_t seed, const Layout& l = {}) {
  cv::RNG rng(seed);
  Synthetic s;
  for (int id = 0; id < identities; ++id) {
    std::vector<float> identity(static_cast<size_t>(l.signals));
    for (float& x : identity) x = static_cast<float>(rng.gaussian(1.0));
    for (int cam = 0; cam < 2; ++cam) {
      std::vector<float> f(static_cast<size_t>(l.dims));
      for (int k = 0; k < l.dims; ++k) {
        const bool signal = k % l.spacing == 0 && k / l.spacing < l.signals;
        f[k] = static_cast<float>(signal ? identity[k / l.spacing] + rng.gaussian(l.camera_noise) : rng.gaussian(l.noise));
      }
      s.features.push_back(f);
      s.ids.push_back(id);
      s.cams.push_back(cam);
    }
  }
  return s;
}

double rank1(const Synthetic& test, const XqdaModel* model) {
  std::vector<std::vector<float>> probes, gallery;
  std::vector<int> pid, gid;
  for (size_t i = 0; i < test.features.size(); ++i) {
    const auto f = model ? model->embed(test.features[i]) : test.features[i];
    (test.cams[i] == 0 ? probes : gallery).push_back(f);
    (test.cams[i] == 0 ? pid : gid).push_back(test.ids[i]);
  }
  cv::Mat sim(static_cast<int>(probes.size()), static_cast<int>(gallery.size()), CV_64F);
  for (int p = 0; p < sim.rows; ++p)
    for (int g = 0; g < sim.cols; ++g) sim.at<double>(p, g) = -squared_distance(probes[p], gallery[g]);
  return ranking_scores(sim, pid, gid, 1).cmc[0];
}

std::vector<XqdaSample> samples_of(const Synthetic& s) {
  std::vector<XqdaSample> samples;
  for (size_t i = 0; i < s.features.size(); ++i) samples.push_back({&s.features[i], s.ids[i], s.cams[i]});
  return samples;
}

// At the ensemble's threshold, over the test's (camera 0, camera 1) pairs: same-person pairs accepted,
// different-person pairs rejected, different-person pairs.
std::tuple<int, int, int> threshold_counts(const XqdaEnsemble& fused, const Synthetic& test) {
  int same_ok = 0, diff_ok = 0, diff_total = 0;
  for (size_t i = 0; i < test.features.size(); i += 2) {
    const auto p = fused.embed(test.features[i]);
    for (size_t j = 1; j < test.features.size(); j += 2) {
      const bool accepted = squared_distance(p, fused.embed(test.features[j])) < fused.threshold;
      if (test.ids[i] == test.ids[j]) same_ok += accepted;
      else diff_ok += !accepted, ++diff_total;
    }
  }
  return {same_ok, diff_ok, diff_total};
}

XqdaModel train(const Synthetic& s) {
  return train_xqda(samples_of(s));
}

TEST(Xqda, LearnsTheDimensionsThatSeparatePeople) {
  const Synthetic training = make_data(60, 1), test = make_data(30, 2);
  const XqdaModel model = train(training);
  const std::vector<XqdaSample> samples = samples_of(training);
  const XqdaEnsemble fused = train_xqda_ensemble(samples, 1);  // threshold chosen on held-out people
  EXPECT_EQ(model.input_length(), 50);
  EXPECT_GE(model.projection.cols, 5);
  const double learned = rank1(test, &model), plain = rank1(test, nullptr);
  EXPECT_GE(learned, 0.9);
  EXPECT_LT(plain, 0.5);
  // The held-out threshold separates most same-person from different-person pairs of unseen people.
  const auto [same_ok, diff_ok, diff_total] = threshold_counts(fused, test);
  EXPECT_GE(same_ok, 24);
  EXPECT_GE(diff_ok, diff_total * 8 / 10);
}

// As on VIPeR, fewer training images (80) than feature dimensions (200): the model pulls its own
// training pairs together, so a threshold picked on them rejects every same-person pair of new people
// (the old calibration accepted 0 of 40 here). Identities differ in every tenth dimension, each image
// has camera noise there and smaller noise in the others.
TEST(Xqda, ThresholdHoldsForUnseenPeopleWhenTrainingIsRankDeficient) {
  const Layout wide{200, 20, 10, 0.5, 0.3};
  const Synthetic training = make_data(40, 3, wide), test = make_data(40, 4, wide);
  const std::vector<XqdaSample> samples = samples_of(training);
  const XqdaEnsemble fused = train_xqda_ensemble(samples, 2);
  const auto [same_ok, diff_ok, diff_total] = threshold_counts(fused, test);
  EXPECT_GE(same_ok, 40 * 6 / 10);  // balanced: most new same-person pairs accepted...
  EXPECT_GE(diff_ok, diff_total * 6 / 10);  // ...and most different-person pairs rejected
}

// The kernel form (Gram matrix in, coefficients on inner products out) is the same model as the
// feature-space one.
TEST(Xqda, KernelFormGivesTheSameEmbedding) {
  const Synthetic training = make_data(30, 7), test = make_data(5, 8);
  const XqdaModel model = train(training);
  cv::Mat a(static_cast<int>(training.features.size()), 50, CV_32F);
  std::vector<XqdaLabel> labels;
  for (size_t i = 0; i < training.features.size(); ++i) {
    std::copy(training.features[i].begin(), training.features[i].end(), a.ptr<float>(static_cast<int>(i)));
    labels.push_back({training.ids[i], training.cams[i]});
  }
  const XqdaFit fit = fit_xqda(gram_matrix(a), labels);
  ASSERT_EQ(fit.coefficients.cols, model.projection.cols);
  EXPECT_DOUBLE_EQ(fit.threshold, model.threshold);
  for (const auto& f : test.features) {
    cv::Mat x(50, 1, CV_32F, const_cast<float*>(f.data())), k;
    cv::Mat(a * x).convertTo(k, CV_64F);
    const cv::Mat e = fit.coefficients.t() * k;
    const std::vector<float> direct = model.embed(f);
    for (int j = 0; j < e.rows; ++j) EXPECT_NEAR(e.at<double>(j), direct[static_cast<size_t>(j)], 1e-3 * (1 + std::abs(direct[static_cast<size_t>(j)])));
  }
}

// Two people in the plane: the same person differs only along y, different people only along x. Both
// solvers keep x alone, with M = 1/lambda - 1/4 there: x0 = (0, 0) and z1 = (2, 0) are 4 (1000 - 0.25)
// apart.
TEST(Xqda, BothSolversKeepTheSeparatingDirectionOfAToyProblem) {
  const std::vector<std::vector<float>> f = {{0, 0}, {0, 1}, {2, 1}, {2, 0}};
  const std::vector<XqdaSample> samples = {{&f[0], 0, 0}, {&f[1], 0, 1}, {&f[2], 1, 0}, {&f[3], 1, 1}};
  for (XqdaSolver solver : {XqdaSolver::kGeneralisedEigen, XqdaSolver::kPublishedSvd}) {
    XqdaOptions options;
    options.solver = solver;
    const XqdaModel model = train_xqda(samples, options);
    ASSERT_EQ(model.projection.cols, 1);
    EXPECT_NEAR(squared_distance(model.embed(f[0]), model.embed(f[3])), 4 * 999.75, 0.05);
    EXPECT_NEAR(squared_distance(model.embed(f[0]), model.embed(f[1])), 0.0, 1e-6);
  }
}

// The published solver against XQDA.m's steps done directly in feature space (pairs enumerated, the
// covariances formed, [W, S] = svd(inCov \ exCov) (W: the left singular vectors), M = inv(W'inCov W) -
// inv(W'exCov W)): the same distances.
TEST(Xqda, PublishedSolverFollowsTheAuthorsSteps) {
  Layout small;
  small.dims = 6, small.signals = 2, small.noise = 0.5, small.camera_noise = 0.3;
  const Synthetic training = make_data(12, 21, small), test = make_data(4, 22, small);
  const int d = small.dims;
  cv::Mat in_cov = cv::Mat::zeros(d, d, CV_64F), ex_cov = cv::Mat::zeros(d, d, CV_64F);
  int n_in = 0, n_ex = 0;
  for (size_t i = 0; i < training.features.size(); ++i)
    for (size_t j = 0; j < training.features.size(); ++j) {
      if (training.cams[i] != 0 || training.cams[j] != 1) continue;
      cv::Mat x(d, 1, CV_32F, const_cast<float*>(training.features[i].data()));
      cv::Mat z(d, 1, CV_32F, const_cast<float*>(training.features[j].data()));
      cv::Mat diff;
      cv::Mat(x - z).convertTo(diff, CV_64F);
      if (training.ids[i] == training.ids[j]) in_cov += diff * diff.t(), ++n_in;
      else ex_cov += diff * diff.t(), ++n_ex;
    }
  in_cov = in_cov / n_in + cv::Mat::eye(d, d, CV_64F) * 1e-3;
  ex_cov = ex_cov / n_ex;
  const cv::SVD svd(cv::Mat(in_cov.inv() * ex_cov), cv::SVD::FULL_UV);
  int k = 0;
  while (k < d && svd.w.at<double>(k) > 1.0) ++k;
  ASSERT_GT(k, 0);
  const cv::Mat w = svd.u.colRange(0, k).clone();
  const cv::Mat m = cv::Mat(w.t() * in_cov * w).inv() - cv::Mat(w.t() * ex_cov * w).inv();

  XqdaOptions options;
  options.solver = XqdaSolver::kPublishedSvd;
  cv::Mat a(static_cast<int>(training.features.size()), d, CV_32F);
  std::vector<XqdaLabel> labels;
  for (size_t i = 0; i < training.features.size(); ++i) {
    std::copy(training.features[i].begin(), training.features[i].end(), a.ptr<float>(static_cast<int>(i)));
    labels.push_back({training.ids[i], training.cams[i]});
  }
  const XqdaFit fit = fit_xqda(gram_matrix(a), labels, options);
  EXPECT_EQ(fit.dims, k);
  ASSERT_EQ(fit.negative_dims, 0);
  const XqdaModel model = train_xqda(samples_of(training), options);
  for (size_t i = 0; i < test.features.size(); i += 2)
    for (size_t j = 1; j < test.features.size(); j += 2) {
      cv::Mat diff;
      cv::Mat(cv::Mat(d, 1, CV_32F, const_cast<float*>(test.features[i].data())) -
              cv::Mat(d, 1, CV_32F, const_cast<float*>(test.features[j].data())))
          .convertTo(diff, CV_64F);
      const cv::Mat p = w.t() * diff;
      const double expected = cv::Mat(p.t() * m * p).at<double>(0);
      EXPECT_NEAR(squared_distance(model.embed(test.features[i]), model.embed(test.features[j])), expected,
                  1e-3 * (1 + expected));
    }
}

TEST(Xqda, EnsembleSlicesMayDifferInLength) {
  const Synthetic s = make_data(20, 9);
  const XqdaEnsemble model = train_xqda_ensemble(samples_of(s), std::vector<int>{20, 30});
  ASSERT_EQ(model.parts.size(), 2u);
  EXPECT_EQ(model.parts[0].input_length(), 20);
  EXPECT_EQ(model.parts[1].input_length(), 30);
  EXPECT_THROW(train_xqda_ensemble(samples_of(s), std::vector<int>{20, 20}), ProcessingError);
  EXPECT_THROW(train_xqda_ensemble(samples_of(s), 3), ProcessingError);  // 50 is not 3 equal slices
}

TEST(Xqda, ModelFileRoundTripsAndBrokenFilesAreInputErrors) {
  const Synthetic s = make_data(20, 3);
  std::vector<XqdaSample> samples;
  for (size_t i = 0; i < s.features.size(); ++i) samples.push_back({&s.features[i], s.ids[i], s.cams[i]});
  XqdaEnsemble model = train_xqda_ensemble(samples, 2);  // two 25-float slices
  ASSERT_EQ(model.parts.size(), 2u);
  EXPECT_EQ(model.input_length(), 50);
  // Projections hold int8 values times a scale per column (what the file stores): every weight of a
  // column is a whole multiple of its largest weight / 127.
  const cv::Mat& p0 = model.parts[0].projection;
  for (int c = 0; c < p0.cols; ++c) {
    double largest = 0;
    cv::minMaxIdx(cv::abs(p0.col(c)), nullptr, &largest);
    ASSERT_GT(largest, 0);
    for (int r = 0; r < p0.rows; ++r) {
      const double steps = p0.at<float>(r, c) / (largest / 127.0);
      EXPECT_NEAR(steps, std::round(steps), 1e-3) << r << "," << c;
    }
  }
  testing::TempDir dir;
  const std::string path = (dir / "model.yml.gz").string();
  EXPECT_THROW(model.save(path), ProcessingError);  // the matcher must say what the features are
  model.features = "synthetic1";
  model.variant = "both-halves";
  model.feature_mean = cv::Mat(1, 3, CV_32F, cv::Scalar(0.25f));
  model.save(path);
  const XqdaEnsemble back = XqdaEnsemble::load(path);
  EXPECT_EQ(back.id, model.id);
  EXPECT_EQ(back.id.size(), 8u);
  EXPECT_EQ(back.features, "synthetic1");
  EXPECT_EQ(back.variant, "both-halves");
  ASSERT_EQ(back.feature_mean.cols, 3);
  EXPECT_FLOAT_EQ(back.feature_mean.at<float>(0, 2), 0.25f);
  EXPECT_DOUBLE_EQ(back.threshold, model.threshold);
  EXPECT_EQ(back.embed(s.features[0]), model.embed(s.features[0]));
  EXPECT_TRUE(testing::contains(testing::input_error([&] { XqdaEnsemble::load((dir / "none.yml").string()); }),
                                "none.yml"));
  testing::write_text(dir / "other.yml", "%YAML:1.0\n---\nformat: something-else\n");
  EXPECT_TRUE(testing::contains(testing::input_error([&] { XqdaEnsemble::load((dir / "other.yml").string()); }),
                                "format"));
  // A model of the previous format (no `features`, so it may come from other features) is refused.
  testing::write_text(dir / "v1.yml", "%YAML:1.0\n---\nformat: bodyrec-xqda\nformat_version: 1\nid: abc\n");
  const std::string v1 = testing::input_error([&] { XqdaEnsemble::load((dir / "v1.yml").string()); });
  EXPECT_TRUE(testing::contains(v1, "format_version' 1")) << v1;
  EXPECT_TRUE(testing::contains(v1, "train-reid")) << v1;
  // Version 2 (float32 projections, lomo3 features) is refused the same way.
  testing::write_text(dir / "v2.yml", "%YAML:1.0\n---\nformat: bodyrec-xqda\nformat_version: 2\nfeatures: lomo3\n");
  EXPECT_TRUE(testing::contains(testing::input_error([&] { XqdaEnsemble::load((dir / "v2.yml").string()); }),
                                "format_version' 2"));
  // A part without its projection names the field, in either readable version.
  testing::write_text(dir / "noproj.yml", "%YAML:1.0\n---\nformat: bodyrec-xqda\nformat_version: 4\nfeatures: x\n"
                                          "threshold: 1.\nparts:\n  - { threshold: 1. }\n");
  EXPECT_TRUE(testing::contains(testing::input_error([&] { XqdaEnsemble::load((dir / "noproj.yml").string()); }),
                                "projection_int8"));
  testing::write_text(dir / "noproj3.yml", "%YAML:1.0\n---\nformat: bodyrec-xqda\nformat_version: 3\nfeatures: x\n"
                                           "threshold: 1.\nparts:\n  - { threshold: 1. }\n");
  EXPECT_TRUE(testing::contains(testing::input_error([&] { XqdaEnsemble::load((dir / "noproj3.yml").string()); }),
                                "projection_float16"));
  // Too few column scales for the projection.
  {
    cv::FileStorage fs((dir / "scales.yml").string(), cv::FileStorage::WRITE);
    fs << "format" << "bodyrec-xqda" << "format_version" << 4 << "features" << "x" << "threshold" << 1.0;
    fs << "parts" << "[" << "{" << "threshold" << 1.0 << "projection_int8" << cv::Mat(4, 3, CV_8S, cv::Scalar(1))
       << "column_scale" << cv::Mat(1, 2, CV_32F, cv::Scalar(0.5f)) << "}" << "]";
  }
  EXPECT_TRUE(testing::contains(testing::input_error([&] { XqdaEnsemble::load((dir / "scales.yml").string()); }),
                                "column_scale"));
  // Version 3 (float16 projections) is still read.
  {
    cv::Mat half;
    cv::Mat(4, 3, CV_32F, cv::Scalar(0.75f)).convertTo(half, CV_16F);
    cv::FileStorage fs((dir / "v3.yml").string(), cv::FileStorage::WRITE);
    fs << "format" << "bodyrec-xqda" << "format_version" << 3 << "features" << "x" << "threshold" << 1.0;
    fs << "parts" << "[" << "{" << "threshold" << 2.0 << "projection_float16"
       << cv::Mat(half.size(), CV_16U, half.data).clone() << "}" << "]";
  }
  const XqdaEnsemble v3 = XqdaEnsemble::load((dir / "v3.yml").string());
  ASSERT_EQ(v3.parts.size(), 1u);
  EXPECT_EQ(v3.input_length(), 4);
  EXPECT_FLOAT_EQ(v3.parts[0].projection.at<float>(3, 2), 0.75f);
  // Version 5 is from a newer build.
  testing::write_text(dir / "v5.yml", "%YAML:1.0\n---\nformat: bodyrec-xqda\nformat_version: 5\nfeatures: x\n");
  EXPECT_TRUE(testing::contains(testing::input_error([&] { XqdaEnsemble::load((dir / "v5.yml").string()); }),
                                "format_version' 5"));
  testing::write_text(dir / "garbage.yml", "\x01\x02 not yaml {{{");
  EXPECT_TRUE(testing::contains(testing::input_error([&] { XqdaEnsemble::load((dir / "garbage.yml").string()); }),
                                "garbage.yml"));
}

TEST(Xqda, RefusesDataThatCannotTrain) {
  const Synthetic s = make_data(3, 4);
  std::vector<XqdaSample> one_camera;
  for (size_t i = 0; i < s.features.size(); i += 2) one_camera.push_back({&s.features[i], s.ids[i], 0});
  EXPECT_THROW(train_xqda(one_camera), ProcessingError);
  EXPECT_THROW(train_xqda({}), ProcessingError);
}

}  // namespace
}  // namespace bodyrec
