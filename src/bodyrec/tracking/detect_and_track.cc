#include "bodyrec/tracking/detect_and_track.h"

#include "bodyrec/core/error.h"

namespace bodyrec {

const char* to_string(BetweenDetections mode) { return mode == BetweenDetections::kPredict ? "predict" : "local"; }

std::optional<BetweenDetections> parse_between_detections(const std::string& text) {
  if (text == "local") return BetweenDetections::kLocal;
  if (text == "predict") return BetweenDetections::kPredict;
  return std::nullopt;
}

void DetectAndTrackOptions::check() const {
  if (detect_every < 1) throw UsageError("DetectAndTrackOptions.detect_every must be >= 1");
  tracker.check();
}

DetectAndTrack::DetectAndTrack(PeopleDetector& detector, const DetectAndTrackOptions& options)
    : detector_(detector), options_(options), tracker_(options.tracker) {
  options_.check();
}

std::vector<TrackedPerson> DetectAndTrack::step(int frame_index, const cv::Mat& image) {
  last_full_ = steps_++ % options_.detect_every == 0;
  if (last_full_) return tracker_.update(frame_index, detector_.detect(image));
  if (options_.between == BetweenDetections::kPredict) return tracker_.predict_only(frame_index);
  // Only tracks matched on the previous frame are searched: a track on still clutter, which the full
  // (motion-region) detector stopped confirming, must not be kept alive by local searches.
  std::vector<Box> expected;
  for (const TrackedPerson& t : tracker_.all_tracks())
    if (t.frames_since_match == 0) expected.push_back(t.box);
  return tracker_.update(frame_index, detector_.detect_near(image, expected), /*may_start_tracks=*/false);
}

}  // namespace bodyrec
