// Online re-identification from a plain camera, frame by frame (thesis Ch6 with colour alone): people from
// a detector and the tracker (tracking/detect_and_track.h), each tracked person's view from the direction
// they walk and faces (walking_view.h), their partial scan cut from the frame with a body mask
// (colour_scan.h) and, with a calibration, their stature; then the same decisions (OnlineReid) on the same
// store (ReidStore) with the same events as the RGB-D pipeline (reid_pipeline.h).
//
// What is lost without depth: bodies come from a detector instead of the sensor's body index (people who
// overlap merge into one foreground blob or are missed; tracks can swap while they cross or jump to
// someone else after a gap: such a track gets a new key where its appearance changes, and a new track
// that clearly continues someone lost a moment ago takes over their key, track_segments.h), scans carry
// whatever the mask lets through (a neighbour's pixels when boxes overlap: such scans lose quality), views
// need people to walk (standing or turning on the spot gives none), the colour bands are spread over the
// crop instead of placed by measured heights, and statures exist only with a calibrated camera
// (`--calibration`), never from a homography.
//
//   ForegroundPeopleDetector people;
//   MemoryReidStore store;   // or GalleryReidStore
//   auto matcher = make_matcher("stripes");
//   ColourReidPipeline reid(people, store, *matcher, {});
//   for (Frame f; source->read(f);) { const ColourReidResult r = reid.process(f); ... r.step.events ... }
//   reid.finish();
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "bodyrec/detection/foreground_detector.h"
#include "bodyrec/io/frame_source.h"
#include "bodyrec/reid/colour_ground.h"
#include "bodyrec/reid/colour_scan.h"
#include "bodyrec/reid/online_reid.h"
#include "bodyrec/reid/track_segments.h"
#include "bodyrec/reid/walking_view.h"
#include "bodyrec/tracking/detect_and_track.h"

namespace bodyrec {

struct ColourReidOptions {
  DetectAndTrackOptions tracking = default_tracking();
  WalkingViewOptions views;
  ColourScanOptions scans;
  OnlineReidOptions reid;
  // Where a track's appearance turns into someone else's, the body gets a new key (track_segments.h).
  TrackSegmentOptions segments;
  // The background model that cuts the bodies out (the default masks) when the detector has none of its own.
  ForegroundOptions foreground;
  void check() const;  // UsageError naming the field
  // Tracking for a cheap detector: the full detector on every frame.
  static DetectAndTrackOptions default_tracking() {
    DetectAndTrackOptions o;
    o.detect_every = 1;
    return o;
  }
};

struct ColourBody {
  uint64_t track = 0;        // the tracker's id
  uint64_t key = 0;          // re-identification key: the tracker's id, new where its appearance changed
  cv::Rect box;              // frame pixels (the tracker's box, rounded, clipped to the frame)
  bool detected = false;     // matched to a detection this frame (else carried by the tracker's prediction)
  ViewEstimate view;
  FaceResult face;
  std::optional<double> stature_m;  // this frame's measurement (calibration only)
  double occluded = 0;       // share of the box covered by other people's boxes
};

struct ColourReidResult {
  std::vector<ColourBody> bodies;  // same order as step.identities
  ReidStep step;
  double ms_detect = 0, ms_scan = 0, ms_reid = 0;  // detection + tracking; views, masks and scans; decisions
};

class ColourReidPipeline {
 public:
  // `detector`, `store`, `matcher` and, when given, `masker` and `ground` must outlive the pipeline.
  // masker null: the foreground inside each box, from the detector's own background model when it is a
  // ForegroundPeopleDetector, else from one the pipeline keeps. UsageError on bad options; InputError when
  // the face cascade cannot be loaded.
  ColourReidPipeline(PeopleDetector& detector, ReidStore& store, const AppearanceMatcher& matcher,
                     const ColourReidOptions& options = {}, BodyMasker* masker = nullptr,
                     const ColourGround* ground = nullptr);
  ~ColourReidPipeline();
  // One frame (BGR, frames in time order, frame.index increasing).
  ColourReidResult process(const Frame& frame);
  // One frame whose bodies are given instead of detected and tracked (diagnosis: a perfect detector and
  // tracker, e.g. true_bodies() of colour_truth.h): each with its track id, box and box-sized mask (CV_8U,
  // 255 = body; empty: the pipeline's masker). The detector still sees the frame (its background model
  // learns), its detections are not used.
  struct GivenBody {
    uint64_t track = 0;
    cv::Rect box;
    cv::Mat mask;
  };
  ColourReidResult process(const Frame& frame, const std::vector<GivenBody>& given);
  // Decides what can be decided and ends every track (`left`).
  std::vector<ReidEvent> finish() { return reid_.finish(); }
  const OnlineReid& decisions() const { return reid_; }
  const TrackSegments& segments() const { return segments_; }

 private:
  // Views, scans, keys and decisions of out.bodies (tracks and boxes set); masks[i] empty: the masker's.
  void identify(const Frame& frame, const std::vector<cv::Mat>& masks, ColourReidResult& out);

  PeopleDetector& detector_;
  ColourReidOptions options_;
  const ColourGround* ground_;
  DetectAndTrack tracking_;
  std::unique_ptr<ForegroundModel> own_foreground_;  // when neither a masker nor a foreground detector
  std::unique_ptr<BodyMasker> own_masker_;
  BodyMasker* masker_;
  WalkingViewEstimator views_;
  TrackSegments segments_;
  OnlineReid reid_;
};

}  // namespace bodyrec
