// Tracking by detection, frame by frame: the full detector runs on every Nth frame; on the frames in
// between, the detector searches only around the tracks matched on the previous frame (or the tracks are
// only predicted). This is how the pipeline gets fast without losing accuracy (docs/benchmarks.md:
// on vtest.avi, every 2nd frame with local searches scores as well as detecting every frame).
//
//   DetectAndTrack tracking(detector, {});
//   for (Frame f; source.read(f);) {
//     const auto tracks = tracking.step(f.index, f.image);  // confirmed + coasting tracks, by id
//   }
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "bodyrec/detection/people_detector.h"
#include "bodyrec/tracking/tracker.h"

namespace bodyrec {

// What happens on the frames between full detections: kLocal = detect_near around the tracks matched on the
// previous frame (detections there only extend tracks, never start one); kPredict = Kalman prediction only.
enum class BetweenDetections { kLocal, kPredict };
const char* to_string(BetweenDetections mode);                             // "local", "predict"
std::optional<BetweenDetections> parse_between_detections(const std::string& text);  // the inverse

struct DetectAndTrackOptions {
  TrackerOptions tracker;
  int detect_every = 2;  // run the full detector on every Nth frame given to step()
  BetweenDetections between = BetweenDetections::kLocal;
  void check() const;  // throws UsageError naming the field
};

class DetectAndTrack {
 public:
  // `detector` must outlive this object; it sees every frame given to step(), in order.
  DetectAndTrack(PeopleDetector& detector, const DetectAndTrackOptions& options);

  // One frame (frame indices increasing). Returns MultiTracker's report for the frame.
  std::vector<TrackedPerson> step(int frame_index, const cv::Mat& image);

  // Whether the last step() ran the full detector.
  bool last_was_full() const { return last_full_; }

 private:
  PeopleDetector& detector_;
  DetectAndTrackOptions options_;
  MultiTracker tracker_;
  long steps_ = 0;
  bool last_full_ = false;
};

}  // namespace bodyrec
