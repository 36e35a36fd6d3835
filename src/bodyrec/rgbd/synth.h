// Synthetic RGB-D people: a small CPU renderer (ray-cast capsules and ellipsoids with a z-buffer) of
// articulated Kinect v2 skeletons with per-person proportions, clothing and accessories, walking through
// a room in scripted scenarios. Frames come out in the recording format with colour, noisy depth, body
// index, bodies (joints and hierarchical orientations) and ground truth.
//
// Conventions: camera space of recording.h (metres, +Y up, u grows with +X); the floor is the plane
// Y = -camera_height. A person's yaw is 0 when facing the camera and +90 when facing -X (towards the
// image's left); forward is R_y(yaw) (0, 0, -1) = (-sin yaw, 0, -cos yaw). SpineBase holds
// R_y(yaw + 180 deg): Kinect's joint frames have Z forward, so a body facing the sensor holds a half turn.
// Every other joint with an orientation holds that rotation turned (minimally) so that its Y axis runs
// along the bone from its parent, as Kinect does; end joints (head, feet, hand tips, thumbs) have none.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bodyrec/rgbd/recording.h"

namespace bodyrec {

// Kinect tracks at most kMaxBodies (6) people at once: body-index slots 0..5 go to people as they come into
// the depth camera's view (the lowest free slot, kept until they are wholly out of view; a freed slot may go
// to someone else). A person in view while all slots are taken is not tracked (no body, 255 in the body
// index, truth body_index -1) until a slot frees.
constexpr int kMaxSynthPeople = 8;

struct SynthOptions {
  int people = 2;                    // 1..kMaxSynthPeople (at most 6 tracked at once)
  uint64_t seed = 1;                 // everything random (looks, paths, noise) derives from it
  // The people's looks (clothes, build, stature) from this seed instead: the same people on other paths
  // (a site's second sensor). None: from `seed`.
  std::optional<uint64_t> looks_seed;
  int frames = 150;                  // the scenario is stretched over this many frames
  std::string scenario = "walk-turn";  // walk-turn, cross, group, reenter, visits
  int color_width = 960, color_height = 540;  // depth is always Kinect v2's 512x424
  // Throws UsageError on values out of range or an unknown scenario.
  void check() const;
};

const std::vector<std::string>& synth_scenarios();

// Frames that give `scenario` with `people` a natural pace at 30 fps: 150, except "visits" (every person
// comes twice, a visit lasting about 5 s): 450 for 1-4 people, growing to 800 for 8.
int synth_recommended_frames(const std::string& scenario, int people);

class Synthesizer {
 public:
  explicit Synthesizer(const SynthOptions& options);
  ~Synthesizer();
  Synthesizer(const Synthesizer&) = delete;
  Synthesizer& operator=(const Synthesizer&) = delete;

  // Sensor description (fps 30, Kinect v2 depth intrinsics, scaled colour intrinsics, streams: all).
  const RecordingMeta& meta() const;
  // Frame `index` (0 <= index < frames). A pure function of the options and the index: the same
  // options give identical frames in any order. Not thread-safe (shares scratch buffers).
  RgbdFrame render(int index);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace bodyrec
