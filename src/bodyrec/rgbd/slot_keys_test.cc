#include "bodyrec/rgbd/slot_keys.h"

#include <gtest/gtest.h>

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace {

constexpr double kFrame = 1.0 / 30;

LabelFloor at(double x, double z, bool side = false) {
  LabelFloor f;
  f.floor = {x, z};
  f.at_side = side;
  f.pixels = f.with_depth = 2000;
  return f;
}

TEST(SlotKeys, SameBodyWalkingKeepsItsKeyAndSlotsDiffer) {
  SlotKeys keys(kFrame);
  const uint64_t k0 = keys.key(0, 0.0, at(0, 2.5));
  const uint64_t k1 = keys.key(1, 0.0, at(1, 3.0));
  EXPECT_EQ(k0, 1000010u);
  EXPECT_EQ(k1, 1000021u);
  for (int f = 1; f < 60; ++f) EXPECT_EQ(keys.key(0, f * kFrame, at(0.04 * f, 2.5)), k0) << "frame " << f;
  // Hidden behind someone for 1 s, shows again 0.5 m on: the same body.
  EXPECT_EQ(keys.key(0, 90 * kFrame, at(2.36 + 0.5, 2.5)), k0);
}

TEST(SlotKeys, WalkingOutAtTheSideAndSomeoneElseInsideGivesANewKey) {
  SlotKeys keys(kFrame);
  const uint64_t k = keys.key(2, 0.0, at(1.8, 3.0));
  EXPECT_EQ(keys.key(2, kFrame, at(1.9, 3.0, true)), k);  // touches the side: still the same body
  // One frame without the slot's body, then a body in the slot 0.9 m inward (within the floor-jump
  // allowance of 1 m + 2 m/s x gap), not at the side: someone else.
  const uint64_t other = keys.key(2, 3 * kFrame, at(1.0, 3.0));
  EXPECT_NE(other, k);
  EXPECT_EQ(other % 10, 2u);
}

TEST(SlotKeys, BackAtTheSideSoonOrStillThereKeepsTheKey) {
  SlotKeys keys(kFrame);
  const uint64_t k = keys.key(3, 0.0, at(1.9, 3.0, true));
  EXPECT_EQ(keys.key(3, kFrame, at(1.8, 3.0)), k);          // stepped in from the side, no frame missed
  EXPECT_EQ(keys.key(3, 2 * kFrame, at(1.9, 3.0, true)), k);
  EXPECT_EQ(keys.key(3, 5 * kFrame, at(1.9, 3.0, true)), k);  // missed 2 frames, shows again at the side
  EXPECT_NE(keys.key(3, 20 * kFrame, at(1.9, 3.0, true)), k);  // gone 0.5 s after the side: walked out
}

TEST(SlotKeys, AFloorJumpOrALongGapGivesANewKey) {
  SlotKeys keys(kFrame);
  const uint64_t k = keys.key(0, 0.0, at(0, 2.0));
  const uint64_t jumped = keys.key(0, kFrame, at(1.5, 2.0));  // 1.5 m in one frame
  EXPECT_NE(jumped, k);
  EXPECT_NE(keys.key(0, 4.0, at(1.5, 2.0)), jumped);  // empty for over 3 s
}

TEST(SlotKeys, BadArgumentsAreUsageErrors) {
  EXPECT_THROW(SlotKeys(0.0), UsageError);
  SlotKeys keys(kFrame);
  EXPECT_THROW(keys.key(6, 0.0, at(0, 2)), UsageError);
  EXPECT_THROW(keys.key(-1, 0.0, at(0, 2)), UsageError);
}

}  // namespace
}  // namespace bodyrec
