// Keys for body-index slots, for a sensor that gives a body index (labels 0..5 per pixel) but no
// tracking ids. The sensor hands a slot to whoever comes next, so a slot is not a person: a slot keeps
// its key while it shows the same body and gets a new one when
//  - it was empty for over a third of a second after its body touched the image's side (it walked out:
//    the slot may go to whoever comes in next), or for over 3 s;
//  - it was empty for a frame or more after its body touched the side, and the body it shows now does
//    not touch the side: whoever walked out would have to cross the side to come back, so this is
//    someone else (who came in elsewhere or stepped out from behind someone);
//  - its body's floor position jumped farther than a walker could go in the time since it was last
//    seen (1 m, a body's width and a half, + 2 m/s x gap): the sensor gave the slot to someone else.
// A body hidden behind someone for a while keeps its key when it shows again near where it vanished.
//
//   SlotKeys keys(1.0 / fps);
//   for (each frame, each slot s with a body)
//     const uint64_t key = keys.key(s, time_s, floor_of_slot_s);
#pragma once

#include <array>
#include <cstdint>

#include <opencv2/core.hpp>

#include "bodyrec/rgbd/skeleton.h"

namespace bodyrec {

// Where one label's body stands in a frame.
struct LabelFloor {
  cv::Vec2d floor{0, 0};  // camera X and Z, metres (valid when with_depth > 0)
  bool at_side = false;   // touches the image's first or last column
  int pixels = 0;         // label pixels
  int with_depth = 0;     // of which with depth
};

class SlotKeys {
 public:
  // `frame_s`: the source's frame period (a gap longer than 1.5 periods means frames without the body).
  explicit SlotKeys(double frame_s);

  // Key of slot `slot` (0..kMaxBodies-1) showing a body at `now` at time `t` (seconds, increasing).
  // ENSURES the same key as the slot's previous call unless one of the rules above gives a new one;
  // keys are >= 1000000, differ between slots, and are never reused.
  uint64_t key(int slot, double t, const LabelFloor& now);

 private:
  struct State {
    uint64_t appearance = 0;
    double t = 0;
    cv::Vec2d floor{0, 0};
    bool at_side = false;
    int pixels = 0;
  };
  double frame_s_;
  std::array<State, kMaxBodies> slots_{};
  uint64_t appearances_ = 0;
};

}  // namespace bodyrec
