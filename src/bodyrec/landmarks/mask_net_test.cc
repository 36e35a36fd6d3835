// The body mask network: crops, a network trained in-test on drawn silhouettes, OpenCV running dlib's
// network, the model file and its errors.
#include "bodyrec/landmarks/mask_net.h"

#include <cmath>
#include <cstdlib>
#include <dlfcn.h>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include <dlib/serialize.h>
#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "bodyrec/core/openblas.h"
#include "bodyrec/landmarks/body_shape.h"
#include "bodyrec/landmarks/body_shape_impl.h"
#include "bodyrec/landmarks/contour.h"
#include "bodyrec/landmarks/landmark_metrics.h"
#include "bodyrec/landmarks/shape_training.h"
#include "silhouette_dataset.h"
#include "test_support.h"

namespace bodyrec {
namespace {

LandmarkDataset drawn_people(int count, uint64_t first_seed) {
  return testing::silhouette_dataset(count, first_seed, 60, cv::Size(120, 150), 120, "drawn");
}

std::string model_bytes(const BodyMaskNet& net) {
  std::ostringstream out;
  net.save(out);
  return out.str();
}

// The bytes of a mask-net model file before its networks: the magic line, the format version, the input
// size and the threshold, then (version 2 on) the count of networks.
std::string model_header(const BodyMaskNet& net, int version, int networks) {
  std::ostringstream out;
  out << "BODYREC-MASKNET\n";
  dlib::serialize(version, out);
  dlib::serialize(net.input_size().width, out);
  dlib::serialize(net.input_size().height, out);
  dlib::serialize(net.threshold(), out);
  if (version >= 2) dlib::serialize(networks, out);
  return out.str();
}

ShapeTrainOptions small_net(int iterations) {
  ShapeTrainOptions o;
  o.method = ShapeMethod::kMaskNet;
  o.net.input_width = 24;
  o.net.input_height = 64;
  o.net.iterations = iterations;
  o.net.batch = 8;
  o.net.learning_rate = 5e-3;
  o.net.threshold = 0;
  o.net.networks = 1;
  return o;
}

TEST(CropBox, ResamplesTheBoxAndReplicatesTheBorder) {
  cv::Mat image(10, 20, CV_8UC3);
  for (int r = 0; r < image.rows; ++r)
    for (int c = 0; c < image.cols; ++c) image.at<cv::Vec3b>(r, c) = cv::Vec3b(2 * c, 2 * r, 7);
  // Inside: a 4x6 box halved by area averaging.
  const cv::Mat half = crop_box(image, Box(2, 2, 4, 6), cv::Size(2, 3));
  ASSERT_EQ(half.size(), cv::Size(2, 3));
  EXPECT_EQ(half.at<cv::Vec3b>(0, 0), cv::Vec3b(5, 5, 7));  // mean of columns 2-3 and rows 2-3
  EXPECT_EQ(half.at<cv::Vec3b>(2, 1), cv::Vec3b(9, 13, 7));  // columns 4-5, rows 6-7
  // Sticking out on the left and the top: the outside copies the nearest border pixel.
  const cv::Mat out = crop_box(image, Box(-3, -2, 5, 4), cv::Size(5, 4));
  EXPECT_EQ(out.at<cv::Vec3b>(0, 0), cv::Vec3b(0, 0, 7));
  EXPECT_EQ(out.at<cv::Vec3b>(3, 4), cv::Vec3b(2, 2, 7));  // image pixel (1, 1)
  // Wholly outside: the nearest image pixel everywhere.
  const cv::Mat far = crop_box(image, Box(40, 30, 4, 4), cv::Size(2, 2));
  EXPECT_EQ(far.at<cv::Vec3b>(1, 1), cv::Vec3b(38, 18, 7));  // image pixel (19, 9)
}

TEST(MaskNet, OptionsAreChecked) {
  MaskNetTrainOptions o;
  EXPECT_NO_THROW(o.check());
  o.input_width = 30;
  EXPECT_TRUE(testing::contains(testing::usage_error([&] { o.check(); }), "MaskNetTrainOptions.input_width"));
  o = MaskNetTrainOptions();
  o.iterations = 0;
  EXPECT_TRUE(testing::contains(testing::usage_error([&] { o.check(); }), "MaskNetTrainOptions.iterations"));
  o = MaskNetTrainOptions();
  o.box_jitter = 0.9;
  EXPECT_TRUE(testing::contains(testing::usage_error([&] { o.check(); }), "MaskNetTrainOptions.box_jitter"));
  o = MaskNetTrainOptions();
  o.weight_decay = -1e-4;
  EXPECT_TRUE(testing::contains(testing::usage_error([&] { o.check(); }), "MaskNetTrainOptions.weight_decay"));
  o.weight_decay = std::nan("");
  EXPECT_TRUE(testing::contains(testing::usage_error([&] { o.check(); }), "MaskNetTrainOptions.weight_decay"));
  for (int networks : {0, kMaxNetworks + 1}) {
    o = MaskNetTrainOptions();
    o.networks = networks;
    EXPECT_TRUE(testing::contains(testing::usage_error([&] { o.check(); }), "MaskNetTrainOptions.networks"));
  }
  EXPECT_THROW(train_body_mask_net(LandmarkDataset{}, MaskNetTrainOptions{}), ProcessingError);
}

TEST(MaskNet, TrainingIsReproducibleInOneProcess) {
  // The initial weights do not depend on what the process trained before (dlib draws them from std::rand).
  const LandmarkDataset data = drawn_people(6, 300);
  MaskNetTrainOptions o = small_net(4).net;
  const std::string first = model_bytes(train_body_mask_net(data, o));
  std::rand();
  EXPECT_TRUE(model_bytes(train_body_mask_net(data, o)) == first);  // (EXPECT_EQ would print the bytes)
  o.seed = 1;  // other augmentation draws
  EXPECT_TRUE(model_bytes(train_body_mask_net(data, o)) != first);
}

TEST(MaskNet, NetworksTrainSideBySideReproducibly) {
  const LandmarkDataset data = drawn_people(6, 300);
  MaskNetTrainOptions o = small_net(4).net;
  // Training leaves OpenBLAS's thread count as it was. (The single network is trained under one BLAS
  // thread as the pair's networks were while dlib's convolutions ran on BLAS; no BLAS call is left now.)
  const auto get_blas = reinterpret_cast<int (*)()>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
  const int blas_threads = get_blas ? get_blas() : 0;
  const BodyMaskNet one = [&] {
    OneBlasThread one_thread;
    return train_body_mask_net(data, o);
  }();
  o.networks = 2;
  const BodyMaskNet pair = train_body_mask_net(data, o);
  if (get_blas) {
    EXPECT_EQ(get_blas(), blas_threads);
  }
  EXPECT_EQ(one.networks(), 1);
  ASSERT_EQ(pair.networks(), 2);
  const std::string single = model_bytes(one), both = model_bytes(pair);
  // Each trainer has its own thread, yet the weights are the same in every run.
  EXPECT_TRUE(model_bytes(train_body_mask_net(data, o)) == both);
  // The first network is the single network of the same seed, the second another.
  const std::string first = single.substr(model_header(one, 2, 1).size());
  ASSERT_EQ(both.substr(0, model_header(pair, 2, 2).size()), model_header(pair, 2, 2));
  EXPECT_TRUE(both.substr(model_header(pair, 2, 2).size(), first.size()) == first);
  EXPECT_TRUE(both.substr(model_header(pair, 2, 2).size() + first.size()) != first);
}

// One network trained once for the tests below (about 30 s in Release); tests/CMakeLists.txt runs the suite
// in one process so that it is trained once.
class TrainedMaskNet : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    train_ = new LandmarkDataset(drawn_people(24, 100));
    model_ = new BodyShapeModel(train_body_shape(*train_, small_net(300)));
  }
  static void TearDownTestSuite() {
    delete model_;
    delete train_;
  }
  // The shared model saved in `dir`: tests change loaded copies, never the shared one.
  static std::string saved(const testing::TempDir& dir) {
    const std::string path = (dir / "model.dat").string();
    if (!std::filesystem::exists(path)) save_body_shape(*model_, path);
    return path;
  }
  static LandmarkDataset* train_;
  static BodyShapeModel* model_;
};
LandmarkDataset* TrainedMaskNet::train_ = nullptr;
BodyShapeModel* TrainedMaskNet::model_ = nullptr;

TEST_F(TrainedMaskNet, RecoversTheOutlinesOfUnseenSilhouettes) {
  EXPECT_EQ(model_->kind(), BodyShapeModel::Kind::kMaskNet);
  EXPECT_EQ(model_->landmarks(), 60);
  const LandmarkDataset test = drawn_people(8, 900);
  const LandmarkScores fit = evaluate_body_shape(*model_, test, "drawn");
  EXPECT_EQ(fit.persons, 8);
  // People are 120 px tall; their outlines are numbered like the truth, so points do not slide.
  std::cout << "mask net on drawn people: " << fit.mean_px << " px, to contour " << fit.contour_px << " px\n";
  EXPECT_LT(fit.mean_px, 4.0);
  EXPECT_LT(fit.contour_px, 2.0);
  // Point 0 is the top of the head: its row is the box's first row.
  const auto& person = test.images[0].people[0];
  const auto points = model_->fit(model_->prepare(test.images[0].image), person.box);
  ASSERT_EQ(points.size(), 60u);
  EXPECT_NEAR(points[0].y, person.box.y, 3.0);
  EXPECT_GT(signed_area2(points), 0);  // clockwise on screen
}

TEST_F(TrainedMaskNet, RunnerRunsTheDlibNetwork) {
  const auto& image = train_->images[0];
  testing::TempDir dir;
  save_body_shape(*model_, (dir / "net.dat").string());
  std::ifstream in(dir / "net.dat", std::ios::binary);
  const BodyMaskNet net(in, "net.dat");
  for (const Box& box : {image.people[0].box, Box(-10, 5, 60, 130), Box(30, 20, 25, 40)}) {
    const cv::Mat fast = net.logits(image.image, box), reference = net.reference_logits(image.image, box);
    ASSERT_EQ(fast.size(), cv::Size(24, 64));
    double range = 0;
    cv::minMaxLoc(cv::abs(reference), nullptr, &range);
    EXPECT_GT(range, 1.0);  // a trained network, not zeros
    EXPECT_LT(cv::norm(fast, reference, cv::NORM_INF), 1e-3 * std::max(1.0, range));
  }
}

TEST_F(TrainedMaskNet, FittingAveragesTheLogitsOfTheBoxAndItsMirrorImage) {
  testing::TempDir dir;
  BodyShapeModel model(saved(dir));
  BodyMaskNet& net = *ShapeModelAccess::impl(model).net;
  EXPECT_TRUE(net.mirror_average());  // the default
  const auto& image = train_->images[4];
  const Box box = image.people[0].box;
  cv::Mat flipped;
  cv::flip(image.image, flipped, 1);
  const Box mirrored(image.image.cols - box.x - box.width, box.y, box.width, box.height);
  cv::Mat back = net.logits(flipped, mirrored);
  cv::flip(back, back, 1);
  const cv::Mat expected = 0.5 * (net.logits(image.image, box) + back);
  const cv::Mat averaged = net.fitting_logits(image.image, box);
  double range = 0;
  cv::minMaxLoc(cv::abs(expected), nullptr, &range);
  EXPECT_GT(range, 1.0);
  // One batch of two equals two passes (to rounding: the crop of the mirror image is resampled apart).
  EXPECT_LT(cv::norm(averaged, expected, cv::NORM_INF), 1e-3 * range);
  EXPECT_GT(cv::norm(averaged, net.logits(image.image, box), cv::NORM_INF), 1e-3 * range);
  // A mirror-symmetric crop gives mirror-symmetric logits.
  cv::Mat symmetric = image.image.clone();
  ASSERT_EQ(symmetric.cols % 2, 0);  // so that a 40 px box centred on it has whole-pixel sides
  const int half = symmetric.cols / 2;
  const cv::Rect left(0, 0, half, symmetric.rows), right(half, 0, half, symmetric.rows);
  cv::flip(symmetric(left), symmetric(right), 1);
  const Box centred(half - 20, box.y, 40, box.height);
  cv::Mat sym = net.fitting_logits(symmetric, centred), sym_flipped;
  cv::flip(sym, sym_flipped, 1);
  EXPECT_LT(cv::norm(sym, sym_flipped, cv::NORM_INF), 1e-3 * range);
  // Off: the network's own logits, and another outline.
  const cv::Mat prepared = model.prepare(image.image);
  const auto with_mirror = net.fit(prepared, box, 60);
  model.set_mirror_average(false);
  EXPECT_FALSE(net.mirror_average());
  EXPECT_EQ(cv::norm(net.fitting_logits(image.image, box), net.logits(image.image, box), cv::NORM_INF), 0.0);
  EXPECT_NE(net.fit(prepared, box, 60), with_mirror);
}

TEST_F(TrainedMaskNet, SavedModelLoadsAndFitsTheSame) {
  testing::TempDir dir;
  const std::string path = (dir / "shape.dat").string();
  save_body_shape(*model_, path);
  const BodyShapeModel loaded(path);
  EXPECT_EQ(loaded.kind_name(), "mask-net");
  EXPECT_EQ(loaded.landmarks(), 60);
  const auto& image = train_->images[3];
  EXPECT_EQ(loaded.fit(loaded.prepare(image.image), image.people[0].box),
            model_->fit(model_->prepare(image.image), image.people[0].box));
  // Grey frames are converted for the network, not refused.
  cv::Mat gray;
  cv::cvtColor(image.image, gray, cv::COLOR_BGR2GRAY);
  EXPECT_EQ(loaded.prepare(gray).type(), CV_8UC3);
}

TEST_F(TrainedMaskNet, ArcOffsetsFromTrainingMoveThePointsAlongTheOutline) {
  const auto& offsets = ShapeModelAccess::impl(*model_).arc_offsets;
  ASSERT_EQ(offsets.size(), 60u);
  double largest = 0;
  for (double o : offsets) largest = std::max(largest, std::abs(o));
  EXPECT_GT(largest, 0.0);
  EXPECT_LT(largest, 0.05);  // drawn people: the fitted outline is numbered almost like the truth
  // A file written before the offsets (none stored) loads and numbers the outline by arc length alone:
  // the same outline, every point moved by its offset.
  testing::TempDir dir;
  const std::string path = (dir / "old.dat").string();
  save_body_shape(*model_, path);
  BodyShapeModel old(path);
  ShapeModelAccess::set_correction(old, ShapeCorrection());  // stored after the offsets: none either
  ShapeModelAccess::set_arc_offsets(old, {});
  save_body_shape(old, path);
  BodyShapeModel loaded(path);
  EXPECT_TRUE(ShapeModelAccess::impl(loaded).arc_offsets.empty());
  // One outline each (by default fit() averages several thresholds' outlines: the next test), without the
  // shape correction (a later test).
  EXPECT_TRUE(ShapeModelAccess::impl(loaded).correction.empty());
  loaded.set_threshold_offsets({0.0});
  BodyShapeModel single(saved(dir));
  single.set_threshold_offsets({0.0});
  single.set_shape_correction(false);
  const auto& image = train_->images[2];
  const auto plain = loaded.fit(loaded.prepare(image.image), image.people[0].box);
  const auto moved = single.fit(single.prepare(image.image), image.people[0].box);
  ASSERT_EQ(plain.size(), moved.size());
  std::vector<double> at(plain.size());
  for (size_t k = 0; k < at.size(); ++k) at[k] = static_cast<double>(k) / at.size() + offsets[k];
  const auto expected = points_at_arc(plain, at);
  for (size_t k = 0; k < plain.size(); ++k) EXPECT_NEAR(cv::norm(moved[k] - expected[k]), 0.0, 1e-9) << k;
}

TEST_F(TrainedMaskNet, FitAveragesTheOutlinesAtEachThresholdOffset) {
  EXPECT_EQ(ShapeModelAccess::impl(*model_).threshold_offsets, kDefaultThresholdOffsets);
  testing::TempDir dir;
  BodyShapeModel model(saved(dir));
  const auto& image = train_->images[5];
  const cv::Mat prepared = model.prepare(image.image);
  const Box box = image.people[0].box;
  const BodyMaskNet& net = *ShapeModelAccess::impl(model).net;
  const std::vector<double>& offsets = ShapeModelAccess::impl(model).arc_offsets;
  const auto outlines = net.fit_at(prepared, box, 60, {-1.0, 0.0, 2.5});
  ASSERT_EQ(outlines.size(), 3u);
  EXPECT_EQ(outlines[1], net.fit(prepared, box, 60));  // offset 0 = the model's own threshold
  EXPECT_NE(outlines[0], outlines[2]);                // a lower threshold gives a wider body
  // Each outline numbered with the arc offsets, then each landmark averaged over them.
  std::vector<double> at(60);
  for (size_t k = 0; k < at.size(); ++k) at[k] = static_cast<double>(k) / at.size() + offsets[k];
  model.set_threshold_offsets({-1.0, 0.0, 2.5});
  model.set_shape_correction(false);  // the next test
  const auto mean = model.fit(prepared, box);
  ASSERT_EQ(mean.size(), 60u);
  for (size_t k = 0; k < mean.size(); ++k) {
    cv::Point2d expected(0, 0);
    for (const auto& outline : outlines) expected += points_at_arc(outline, at)[k] / 3.0;
    EXPECT_NEAR(cv::norm(mean[k] - expected), 0.0, 1e-9) << k;
  }
  // The averaged points still recover the drawn people (as the single outline does above).
  model.set_threshold_offsets(kDefaultThresholdOffsets);
  model.set_shape_correction(true);
  EXPECT_LT(evaluate_body_shape(model, drawn_people(8, 900), "drawn").mean_px, 4.0);
  // Bad lists are usage errors naming the option.
  EXPECT_TRUE(testing::contains(testing::usage_error([&] { model.set_threshold_offsets({}); }), "--threshold-offsets"));
  EXPECT_TRUE(testing::contains(testing::usage_error([&] { model.set_threshold_offsets({0.0, NAN}); }), "finite"));
}

TEST_F(TrainedMaskNet, ShapeCorrectionFromTrainingMovesTheAveragedPoints) {
  const ShapeCorrection& correction = ShapeModelAccess::impl(*model_).correction;
  ASSERT_FALSE(correction.empty());
  EXPECT_EQ(correction.landmarks(), 60);
  testing::TempDir dir;
  BodyShapeModel without(saved(dir));
  without.set_shape_correction(false);
  const auto& image = train_->images[6];
  const Box box = image.people[0].box;
  const auto plain = without.fit(without.prepare(image.image), box);
  const auto corrected = model_->fit(model_->prepare(image.image), box);
  const auto expected = correction.apply(plain, box);
  ASSERT_EQ(corrected.size(), 60u);
  double moved = 0;
  for (size_t k = 0; k < corrected.size(); ++k) {
    EXPECT_NEAR(cv::norm(corrected[k] - expected[k]), 0.0, 1e-9) << k;
    moved += cv::norm(corrected[k] - plain[k]) / 60;
  }
  EXPECT_GT(moved, 0.01);  // it does something...
  EXPECT_LT(moved, 3.0);   // ...but little on drawn people, whose outlines are numbered almost like the truth
  // The saved model applies the same correction.
  const BodyShapeModel loaded(saved(dir));
  EXPECT_EQ(loaded.fit(loaded.prepare(image.image), box), corrected);
  // Ridge regression lowers the squared error (box units) on the people it was learnt on.
  double before = 0, after = 0;
  for (const auto& im : train_->images) {
    for (const auto& person : im.people) {
      const auto p0 = without.fit(without.prepare(im.image), person.box);
      const auto p1 = model_->fit(model_->prepare(im.image), person.box);
      for (size_t k = 0; k < p0.size(); ++k) {
        const cv::Point2d e0 = (p0[k] - person.landmarks[k]) / person.box.height;
        const cv::Point2d e1 = (p1[k] - person.landmarks[k]) / person.box.height;
        before += e0.dot(e0);
        after += e1.dot(e1);
      }
    }
  }
  EXPECT_LT(after, before);
  // The trees have no correction to leave out.
  EXPECT_TRUE(testing::contains(testing::usage_error([&] {
                                  BodyShapeModel trees = ShapeModelAccess::make(dlib::shape_predictor());
                                  trees.set_shape_correction(false);
                                }),
                                "--no-correction applies to mask-net models only"));
}

TEST_F(TrainedMaskNet, LegSlitIsAFittingOptionOnByDefault) {
  testing::TempDir dir;
  BodyShapeModel model(saved(dir));
  const BodyMaskNet& net = *ShapeModelAccess::impl(model).net;
  EXPECT_TRUE(net.leg_slit());
  // Off: each outline is the thresholded mask's own. The slit only ever adds the way up between the legs
  // and back, so the outline with it is at least as long (400 points: the polygon follows the outline).
  const auto& image = train_->images[4];
  const cv::Mat prepared = model.prepare(image.image);
  const Box box = image.people[0].box;
  const double with_slit = closed_length(net.fit_at(prepared, box, 400, {0.0}).front());
  model.set_leg_slit(false);
  EXPECT_FALSE(net.leg_slit());
  EXPECT_GE(with_slit + 1.0, closed_length(net.fit_at(prepared, box, 400, {0.0}).front()));
  // The loaded model has it on again (an option, not saved).
  EXPECT_TRUE(ShapeModelAccess::impl(BodyShapeModel(saved(dir))).net->leg_slit());
  EXPECT_TRUE(testing::contains(testing::usage_error([&] {
                                  BodyShapeModel trees = ShapeModelAccess::make(dlib::shape_predictor());
                                  trees.set_leg_slit(false);
                                }),
                                "--no-leg-slit applies to mask-net models only"));
}

TEST_F(TrainedMaskNet, BrokenModelFilesNameTheFile) {
  testing::TempDir dir;
  const std::string good = (dir / "good.dat").string();
  save_body_shape(*model_, good);
  std::ifstream in(good, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // Truncated in the network, and cut in the shape correction at the end.
  testing::write_text(dir / "cut.dat", bytes.substr(0, bytes.size() / 2));
  const std::string cut = testing::input_error([&] { BodyShapeModel m((dir / "cut.dat").string()); });
  EXPECT_TRUE(testing::contains(cut, "cut.dat")) << cut;
  EXPECT_TRUE(testing::contains(cut, "truncated or corrupt")) << cut;
  testing::write_text(dir / "cutcorrection.dat", bytes.substr(0, bytes.size() - 1));
  const std::string correction =
      testing::input_error([&] { BodyShapeModel m((dir / "cutcorrection.dat").string()); });
  EXPECT_TRUE(testing::contains(correction, "cutcorrection.dat: truncated mask-net model (shape correction)"))
      << correction;
  // A file written before the shape correction ends after the arc offsets: it loads; cut in the offsets.
  BodyShapeModel older(good);
  ShapeModelAccess::set_correction(older, ShapeCorrection());
  save_body_shape(older, (dir / "older.dat").string());
  EXPECT_TRUE(ShapeModelAccess::impl(BodyShapeModel((dir / "older.dat").string())).correction.empty());
  std::ifstream older_in(dir / "older.dat", std::ios::binary);
  const std::string older_bytes((std::istreambuf_iterator<char>(older_in)), std::istreambuf_iterator<char>());
  testing::write_text(dir / "nooffsets.dat", older_bytes.substr(0, older_bytes.size() - 1));
  const std::string offsets = testing::input_error([&] { BodyShapeModel m((dir / "nooffsets.dat").string()); });
  EXPECT_TRUE(testing::contains(offsets, "nooffsets.dat")) << offsets;
  EXPECT_TRUE(testing::contains(offsets, "arc offsets")) << offsets;
  // Offsets that do not fit the landmarks.
  BodyShapeModel odd(good);
  ShapeModelAccess::set_arc_offsets(odd, {0.0, 0.1, 0.2});
  save_body_shape(odd, (dir / "odd.dat").string());
  EXPECT_TRUE(testing::contains(testing::input_error([&] { BodyShapeModel m((dir / "odd.dat").string()); }),
                                "invalid arc offsets"));
  // A future format version.
  std::string future = bytes;
  future[16 + 1] = 9;  // dlib's int encoding: a size byte, then the value's bytes
  testing::write_text(dir / "future.dat", future);
  const std::string version = testing::input_error([&] { BodyShapeModel m((dir / "future.dat").string()); });
  EXPECT_TRUE(testing::contains(version, "version 9")) << version;
  // Only the magic bytes.
  testing::write_text(dir / "magic.dat", bytes.substr(0, 16));
  EXPECT_TRUE(testing::contains(testing::input_error([&] { BodyShapeModel m((dir / "magic.dat").string()); }),
                                "magic.dat"));
}

TEST_F(TrainedMaskNet, ModelFilesCountTheirNetworksAndFittingAveragesThem) {
  const BodyMaskNet& net = *ShapeModelAccess::impl(*model_).net;
  const std::string bytes = model_bytes(net);
  ASSERT_EQ(bytes.substr(0, model_header(net, 2, 1).size()), model_header(net, 2, 1));
  const std::string weights = bytes.substr(model_header(net, 2, 1).size());
  const auto load = [](const std::string& file, const std::string& name) {
    std::istringstream in(file);
    return BodyMaskNet(in, name);
  };
  const auto& image = train_->images[2];
  const Box box = image.people[0].box;
  const cv::Mat logits = net.logits(image.image, box), reference = net.reference_logits(image.image, box);
  // Format version 1 had one network and no count.
  const BodyMaskNet old = load(model_header(net, 1, 1) + weights, "v1.dat");
  EXPECT_EQ(old.networks(), 1);
  EXPECT_EQ(cv::norm(old.logits(image.image, box), logits, cv::NORM_INF), 0.0);
  // The same network twice: the mean of two equal logits is each (run side by side, and in dlib).
  const BodyMaskNet twice = load(model_header(net, 2, 2) + weights + weights, "twice.dat");
  EXPECT_EQ(twice.networks(), 2);
  EXPECT_EQ(cv::norm(twice.logits(image.image, box), logits, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(twice.fitting_logits(image.image, box), net.fitting_logits(image.image, box), cv::NORM_INF), 0.0);
  EXPECT_LT(cv::norm(twice.reference_logits(image.image, box), reference, cv::NORM_INF), 1e-6);
  EXPECT_EQ(twice.fit(image.image, box, 60), net.fit(image.image, box, 60));
  // A count out of range, and a file that ends in the second network.
  for (int count : {0, kMaxNetworks + 1}) {
    const std::string why = testing::input_error([&] { load(model_header(net, 2, count) + weights, "count.dat"); });
    EXPECT_TRUE(testing::contains(why, "count.dat: mask-net model has " + std::to_string(count) + " networks")) << why;
  }
  const std::string cut = testing::input_error(
      [&] { load(model_header(net, 2, 2) + weights + weights.substr(0, weights.size() / 2), "cut.dat"); });
  EXPECT_TRUE(testing::contains(cut, "cut.dat: truncated or corrupt")) << cut;
}

TEST(MaskNet, RecogniseLeavesTheStreamWhereItWas) {
  std::istringstream other("not a model at all");
  EXPECT_FALSE(BodyMaskNet::recognise(other));
  EXPECT_EQ(other.tellg(), 0);
  std::istringstream tiny("BODY");
  EXPECT_FALSE(BodyMaskNet::recognise(tiny));
  EXPECT_EQ(tiny.tellg(), 0);
  EXPECT_TRUE(testing::contains(testing::input_error([&] { BodyMaskNet n(other, "x.dat"); }), "x.dat"));
}

}  // namespace
}  // namespace bodyrec
