#include "bodyrec/io/live_frames.h"

#include <atomic>
#include <vector>

#include <gtest/gtest.h>

namespace bodyrec {
namespace {

using namespace std::chrono_literals;

struct Numbered {
  int index = 0;
  double time_s = 0;
};

// A source of n frames, `interval_s` apart in time.
LiveFrames<Numbered>::Reader numbers(int n, double interval_s, std::atomic<int>* read = nullptr) {
  auto next = std::make_shared<int>(0);
  return [=](Numbered& f) {
    if (*next >= n) return false;
    f.index = *next;
    f.time_s = *next * interval_s;
    ++*next;
    if (read) ++*read;
    return true;
  };
}

double time_of(const Numbered& f) { return f.time_s; }

TEST(LiveFrames, ARoomyHandOverDeliversEveryFrameInOrder) {
  LiveFrames<Numbered> live(numbers(10, 0.0), {100, false});
  std::vector<int> got;
  for (Arrived<Numbered> a; live.next(a) == LiveNext::kFrame;) got.push_back(a.frame.index);
  ASSERT_EQ(got.size(), 10u);
  for (int i = 0; i < 10; ++i) EXPECT_EQ(got[static_cast<size_t>(i)], i);
  EXPECT_EQ(live.dropped(), 0);
}

// A consumer five times slower than the source: frames are dropped, counted, and the loop always gets the
// newest; taken + dropped = every frame, nothing is delayed without bound.
TEST(LiveFrames, ASlowConsumerDropsTheOldestAndCountsThem) {
  const int n = 30;
  LiveFrames<Numbered> live(numbers(n, 0.01), {1, true}, time_of);
  std::vector<int> got;
  long last_dropped = 0;
  for (Arrived<Numbered> a; live.next(a) == LiveNext::kFrame;) {
    got.push_back(a.frame.index);
    EXPECT_GE(a.dropped, last_dropped);
    last_dropped = a.dropped;
    std::this_thread::sleep_for(50ms);  // the slow stage
  }
  EXPECT_GT(live.dropped(), n / 2);
  EXPECT_EQ(static_cast<long>(got.size()) + live.dropped(), n);
  EXPECT_EQ(got.back(), n - 1);  // the last frame is never dropped
  for (size_t i = 1; i < got.size(); ++i) EXPECT_GT(got[i], got[i - 1]);
  EXPECT_EQ(live.delivered(), n);
}

// Paced: frames come at their own times, not as fast as they are read.
TEST(LiveFrames, PacedFramesArriveAtTheirOwnTimes) {
  LiveFrames<Numbered> live(numbers(6, 0.05), {4, true}, time_of);
  std::vector<std::chrono::steady_clock::time_point> at;
  for (Arrived<Numbered> a; live.next(a) == LiveNext::kFrame;) at.push_back(a.arrived);
  ASSERT_EQ(at.size(), 6u);
  for (size_t i = 1; i < at.size(); ++i) {
    // Never early (a sleep never returns before its time): frame i at least i x 50 ms after frame 0.
    EXPECT_GE(at[i] - at[0], std::chrono::milliseconds(50 * static_cast<int>(i))) << i;
  }
  EXPECT_EQ(live.dropped(), 0);
}

TEST(LiveFrames, UnpacedFramesComeAsFastAsTheyAreRead) {
  LiveFrames<Numbered> live(numbers(6, 10.0), {8, false});  // 10 s apart in time: unpaced, no waiting
  const auto t0 = std::chrono::steady_clock::now();
  int n = 0;
  for (Arrived<Numbered> a; live.next(a) == LiveNext::kFrame;) ++n;
  EXPECT_EQ(n, 6);
  EXPECT_LT(std::chrono::steady_clock::now() - t0, 10s);
}

TEST(LiveFrames, AReadersErrorComesAfterTheFramesBeforeIt) {
  auto next = std::make_shared<int>(0);
  LiveFrames<Numbered> live(
      [next](Numbered& f) {
        if (*next == 3) throw InputError("frame 3: broken");
        f.index = (*next)++;
        return true;
      },
      {10, false});
  std::vector<int> got;
  Arrived<Numbered> a;
  try {
    while (live.next(a) == LiveNext::kFrame) got.push_back(a.frame.index);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "frame 3: broken");
  }
  EXPECT_EQ(got, (std::vector<int>{0, 1, 2}));
}

TEST(LiveFrames, StopEndsAnEndlessSourceAndNextTimesOut) {
  std::atomic<int> read{0};
  LiveFrames<Numbered> live(
      [&read](Numbered& f) {
        std::this_thread::sleep_for(20ms);
        f.index = read++;
        return true;
      },
      {1, false});
  Arrived<Numbered> a;
  EXPECT_EQ(live.next(a, 1ms), LiveNext::kTimeout);  // the first read takes 20 ms
  ASSERT_EQ(live.next(a), LiveNext::kFrame);
  live.stop();
  const int after_stop = read.load();
  while (live.next(a) == LiveNext::kFrame) {
  }
  EXPECT_EQ(live.next(a, 1ms), LiveNext::kEnd);
  std::this_thread::sleep_for(60ms);
  EXPECT_EQ(read.load(), after_stop);  // the grabber is gone
}

TEST(LiveFrames, BadOptionsAreRefused) {
  EXPECT_THROW(LiveFrames<Numbered>(numbers(1, 0), {0, false}), UsageError);
  EXPECT_THROW(LiveFrames<Numbered>(numbers(1, 0), {1, true}), UsageError);  // pace without times
}

}  // namespace
}  // namespace bodyrec
