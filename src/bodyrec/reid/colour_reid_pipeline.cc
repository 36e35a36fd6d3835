#include "bodyrec/reid/colour_reid_pipeline.h"

#include <chrono>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

cv::Rect pixel_box(const Box& b, const cv::Size& size) {
  const cv::Rect r(cv::Point(static_cast<int>(std::lround(b.x)), static_cast<int>(std::lround(b.y))),
                   cv::Point(static_cast<int>(std::lround(b.br().x)), static_cast<int>(std::lround(b.br().y))));
  return r & cv::Rect(0, 0, size.width, size.height);
}

}  // namespace

void ColourReidOptions::check() const {
  tracking.check();
  views.check();
  scans.check();
  reid.check();
  segments.check();
  foreground.check();
}

ColourReidPipeline::ColourReidPipeline(PeopleDetector& detector, ReidStore& store, const AppearanceMatcher& matcher,
                                       const ColourReidOptions& options, BodyMasker* masker, const ColourGround* ground)
    : detector_(detector),
      options_((options.check(), options)),
      ground_(ground),
      tracking_(detector, options.tracking),
      masker_(masker),
      views_(options.views, ground),
      segments_(matcher, options.segments),
      reid_(store, matcher, options.reid) {
  if (!masker_) {
    const auto* foreground = dynamic_cast<const ForegroundPeopleDetector*>(&detector_);
    if (!foreground) own_foreground_ = std::make_unique<ForegroundModel>(options_.foreground);
    own_masker_ = std::make_unique<ForegroundBodyMask>(foreground ? foreground->model() : *own_foreground_);
    masker_ = own_masker_.get();
  }
}

ColourReidPipeline::~ColourReidPipeline() = default;

ColourReidResult ColourReidPipeline::process(const Frame& frame) {
  if (frame.image.empty() || frame.image.type() != CV_8UC3)
    throw InputError(frame.name + ": frame " + std::to_string(frame.index) + " is not a BGR image");
  ColourReidResult out;
  auto t0 = std::chrono::steady_clock::now();
  const std::vector<TrackedPerson> tracks = tracking_.step(frame.index, frame.image);
  if (own_foreground_) own_foreground_->update(frame.image);
  out.ms_detect = ms_since(t0);

  const cv::Size size = frame.image.size();
  for (const TrackedPerson& t : tracks) {
    if (t.id < 0) continue;
    ColourBody b;
    b.track = static_cast<uint64_t>(t.id);
    b.box = pixel_box(t.box, size);
    b.detected = t.frames_since_match == 0;
    if (!b.box.empty()) out.bodies.push_back(b);
  }
  identify(frame, std::vector<cv::Mat>(out.bodies.size()), out);
  return out;
}

ColourReidResult ColourReidPipeline::process(const Frame& frame, const std::vector<GivenBody>& given) {
  if (frame.image.empty() || frame.image.type() != CV_8UC3)
    throw InputError(frame.name + ": frame " + std::to_string(frame.index) + " is not a BGR image");
  ColourReidResult out;
  // The masker's background model learns every frame, as with detected bodies.
  auto t0 = std::chrono::steady_clock::now();
  detector_.detect(frame.image);
  if (own_foreground_) own_foreground_->update(frame.image);
  out.ms_detect = ms_since(t0);
  std::vector<cv::Mat> masks;
  const cv::Rect all(0, 0, frame.image.cols, frame.image.rows);
  for (const GivenBody& g : given) {
    ColourBody b;
    b.track = g.track;
    b.box = g.box & all;
    b.detected = true;
    if (b.box.empty()) continue;
    if (!g.mask.empty() && (b.box != g.box || g.mask.size() != g.box.size()))
      throw InputError(frame.name + ": frame " + std::to_string(frame.index) + ": a given mask does not match its box");
    out.bodies.push_back(b);
    masks.push_back(g.mask);
  }
  identify(frame, masks, out);
  return out;
}

void ColourReidPipeline::identify(const Frame& frame, const std::vector<cv::Mat>& masks, ColourReidResult& out) {
  auto t0 = std::chrono::steady_clock::now();
  const cv::Size size = frame.image.size();
  segments_.next_frame();
  // The share of each box that others cover (their pixels are in its mask).
  for (ColourBody& b : out.bodies) {
    double covered = 0;
    for (const ColourBody& o : out.bodies)
      if (&o != &b) covered += (b.box & o.box).area();
    b.occluded = std::min(1.0, covered / std::max(1, b.box.area()));
  }
  std::vector<ReidBody> bodies;
  for (size_t i = 0; i < out.bodies.size(); ++i) {
    ColourBody& b = out.bodies[i];
    b.view = views_.estimate(b.track, frame.time_s, b.box, frame.image);
    b.face = views_.last_face();
    ReidBody rb;
    rb.view = b.view;
    rb.box = b.box;
    // Every detected body is scanned while segments watch its appearance; else only when the decisions
    // want a scan of it (the key is then the track's current one).
    std::optional<PartialScan> scan;
    const bool watch = options_.segments.enabled;
    if (b.detected && (watch || reid_.wants_scan(segments_.key(b.track, nullptr), b.view))) {
      const cv::Mat mask = masks[i].empty() ? masker_->mask(frame.image, b.box) : masks[i];
      if (ground_ && !mask.empty() && b.occluded < 0.05) {
        // Stature from the mask's top and bottom rows, when the body is whole in the frame.
        std::vector<cv::Point> points;
        cv::findNonZero(largest_part(mask), points);
        if (!points.empty()) {
          const cv::Rect tight = cv::boundingRect(points) + b.box.tl();
          if (tight.y > 0 && tight.br().y < size.height) {
            const double x = tight.x + tight.width / 2.0;
            b.stature_m = ground_->stature_m({x, static_cast<double>(tight.br().y)}, {x, static_cast<double>(tight.y)});
          }
        }
      }
      scan = colour_scan(frame.image, b.box, mask, b.view, b.occluded, b.stature_m, options_.scans);
    }
    b.key = segments_.key(b.track, scan ? &*scan : nullptr);
    rb.track = b.key;
    if (scan && reid_.wants_scan(b.key, b.view)) {
      rb.scan = std::move(scan);
      rb.stature_m = b.stature_m;
    }
    bodies.push_back(std::move(rb));
  }
  views_.forget_before(frame.time_s);
  out.ms_scan = ms_since(t0);

  t0 = std::chrono::steady_clock::now();
  out.step = reid_.step(frame.time_s, bodies);
  out.ms_reid = ms_since(t0);
}

}  // namespace bodyrec
