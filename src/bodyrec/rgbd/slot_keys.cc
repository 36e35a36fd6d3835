#include "bodyrec/rgbd/slot_keys.h"

#include "bodyrec/core/error.h"

namespace bodyrec {

SlotKeys::SlotKeys(double frame_s) : frame_s_(frame_s) {
  if (!(frame_s > 0)) throw UsageError("slot keys: the frame period must be positive");
}

uint64_t SlotKeys::key(int slot, double t, const LabelFloor& now) {
  if (slot < 0 || slot >= kMaxBodies) throw UsageError("slot keys: slot " + std::to_string(slot) + " is not 0..5");
  State& s = slots_[static_cast<size_t>(slot)];
  const double gap = t - s.t;
  const bool missed = gap > 1.5 * frame_s_;  // at least one frame without this slot's body
  const bool walked_out = s.at_side && ((missed && !now.at_side) || gap > 1.0 / 3.0);
  const bool jumped = now.with_depth && s.pixels && cv::norm(now.floor - s.floor) > 1.0 + 2.0 * gap;
  if (!s.appearance || gap > 3.0 || walked_out || jumped) s.appearance = ++appearances_;
  s.t = t;
  s.at_side = now.at_side;
  if (now.with_depth) s.floor = now.floor, s.pixels = now.with_depth;
  return 1000000 + 10 * s.appearance + static_cast<uint64_t>(slot);
}

}  // namespace bodyrec
