// run_reid (reid_job.h): the frame loop of `reid` and `eval reid-stream` over an RGB-D source (ReidPipeline)
// or a colour one (ColourReidPipeline), live sources through the grabber (frame_loop.h).
#include <algorithm>
#include <cmath>
#include <thread>

#include "bodyrec/reid/colour_truth.h"
#include "frame_errors.h"
#include "reid_job.h"

namespace bodyrec::cli {
namespace {

// What every frame goes through after its pipeline: the sink, then the latency of its events (the sink has
// written and flushed them).
struct AfterFrame {
  ReidRunStats& stats;
  const std::function<void(const ReidFrame&)>& sink;
  void operator()(const ReidFrame& f) const {
    sink(f);
    if (!f.arrival) return;
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - f.arrival->at).count();
    for (size_t i = 0; i < f.step.events.size(); ++i) stats.latency_ms.push_back(ms);
  }
};

void slow_stage(const LiveCliOptions& live) {
  if (live.test_delay_ms > 0) std::this_thread::sleep_for(std::chrono::milliseconds(live.test_delay_ms));
}

void finish(const std::vector<ReidEvent>& events, const std::function<void(const ReidFrame&)>& sink) {
  RgbdFrame end;
  end.index = -1;
  ReidStep last;
  last.events = events;
  const std::vector<OrientedBody> none;
  sink({end, none, last});
}

ReidRunStats run_rgbd_reid(ReidInput& input, const ReidCliOptions& options, ReidStore& store,
                           const std::function<void(const ReidFrame&)>& sink) {
  ReidPipelineOptions po;
  po.orient = options.orient.pipeline;
  po.reid = options.reid;
  po.reid.all_views = match_views(options) == MatchViews::kAll;
  if (options.stature_wait >= 0) po.stature_wait_frames = options.stature_wait;
  OrientSource& source = *input.source;
  ReidPipeline pipeline(source.meta(), store, *input.matcher, po, source.segmenter(options.orient), source.name());
  const LiveCliOptions& live = options.orient.live;
  ReidRunStats stats;
  const AfterFrame after{stats, sink};
  const FrameLoopStats loop = run_frame_loop<RgbdFrame>(
      [&source](RgbdFrame& f) { return source.read(f); }, [](const RgbdFrame& f) { return f.time_s; },
      loop_options(live, options.orient.max_frames), [&](RgbdFrame& f, const FrameArrival& arrival) {
        slow_stage(live);
        const ReidResult r = pipeline.process(f);
        after({f, r.bodies, r.step, r.ms_orient, r.ms_scan, r.ms_reid, &arrival, false, live.live()});
      });
  stats.frames = loop.frames;
  stats.dropped = loop.dropped;
  stats.stopped = loop.stopped;
  finish(pipeline.finish(), sink);
  return stats;
}

ReidRunStats run_colour_reid(ReidInput& input, const ReidCliOptions& options, ReidStore& store,
                             const std::function<void(const ReidFrame&)>& sink) {
  ColourInput& c = *input.colour;
  c.options.reid.all_views = match_views(options) == MatchViews::kAll;
  ListedDetector listed;  // --true-bodies detections
  const bool listing = input.true_bodies == ReidInput::TrueBodies::kDetections && input.source;
  ColourReidPipeline pipeline(listing ? listed : *c.detector, store, *input.matcher, c.options, c.masker.get(), c.ground.get());
  const LiveCliOptions& live = options.orient.live;
  FrameLoopOptions lo = loop_options(live, options.orient.max_frames);
  const bool is_live = lo.live || options.colour.camera >= 0;
  lo.live = is_live;
  ReidRunStats stats;
  const AfterFrame after{stats, sink};
  const auto process = [&](const RgbdFrame& rf, const Frame& f, const FrameArrival& arrival) {
    slow_stage(live);
    ColourReidResult r;
    if (listing) {
      std::vector<cv::Rect> boxes;
      for (const TrueBody& t : true_bodies(input.source->meta(), rf)) boxes.push_back(t.box);
      listed.set(boxes);
      r = pipeline.process(f);
    } else if (input.true_bodies != ReidInput::TrueBodies::kNone && input.source) {
      std::vector<ColourReidPipeline::GivenBody> given;
      const bool masks = input.true_bodies == ReidInput::TrueBodies::kMasks;
      for (TrueBody& t : true_bodies(input.source->meta(), rf))
        given.push_back({t.track, t.box, masks ? t.mask : cv::Mat()});
      r = pipeline.process(f, given);
    } else {
      r = pipeline.process(f);
    }
    std::vector<OrientedBody> bodies;
    for (const ColourBody& b : r.bodies) {
      OrientedBody o;
      o.key = b.key;
      o.view = b.view;
      o.face = b.face;
      bodies.push_back(o);
    }
    int visible = -1;
    if (input.score_truth && input.source && rf.truth) {
      std::vector<cv::Rect> boxes;
      for (const ColourBody& b : r.bodies) boxes.push_back(b.box);
      const BoxTruth t = truth_for_boxes(input.source->meta(), rf, boxes);
      for (size_t i = 0; i < bodies.size(); ++i) bodies[i].truth = t.person[i];
      visible = t.visible;
    }
    after({rf, bodies, r.step, r.ms_detect, r.ms_scan, r.ms_reid, &arrival, true, is_live, visible});
  };
  FrameLoopStats loop;
  if (c.frames) {
    const auto read = [&c](Frame& f) {
      if (!c.frames->read(f)) return false;
      if (c.image_fps) f.time_s = f.index / *c.image_fps;
      return true;
    };
    loop = run_frame_loop<Frame>(read, [](const Frame& f) { return f.time_s; },
                                 lo, [&](Frame& f, const FrameArrival& arrival) {
                                   RgbdFrame rf;
                                   rf.index = f.index;
                                   rf.time_s = f.time_s;
                                   rf.color = f.image;
                                   naming_frame(f, [&] { process(rf, f, arrival); });
                                 });
  } else {
    OrientSource& source = *input.source;
    loop = run_frame_loop<RgbdFrame>([&source](RgbdFrame& f) { return source.read(f); },
                                     [](const RgbdFrame& f) { return f.time_s; }, lo,
                                     [&](RgbdFrame& rf, const FrameArrival& arrival) {
                                       Frame f;
                                       f.image = rf.color;
                                       f.index = rf.index;
                                       f.time_s = rf.time_s;
                                       f.name = source.name() + "#" + std::to_string(rf.index);
                                       process(rf, f, arrival);
                                     });
  }
  stats.frames = loop.frames;
  stats.dropped = loop.dropped;
  stats.stopped = loop.stopped;
  finish(pipeline.finish(), sink);
  return stats;
}

}  // namespace

ReidRunStats run_reid(ReidInput& input, const ReidCliOptions& options, ReidStore& store,
                      const std::function<void(const ReidFrame&)>& sink) {
  return input.colour ? run_colour_reid(input, options, store, sink) : run_rgbd_reid(input, options, store, sink);
}

}  // namespace bodyrec::cli
