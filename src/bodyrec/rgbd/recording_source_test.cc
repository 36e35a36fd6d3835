#include <gtest/gtest.h>

#include "bodyrec/rgbd/recording_source.h"
#include "bodyrec/rgbd/synth.h"
#include "test_support.h"

namespace bodyrec {
namespace {

using bodyrec::testing::contains;
using bodyrec::testing::input_error;
using bodyrec::testing::TempDir;

TEST(RecordingFrameSource, DeliversTheColourStreamWithSelection) {
  TempDir dir;
  SynthOptions o;
  o.frames = 10;
  o.color_width = 160;
  o.color_height = 90;
  Synthesizer synth(o);
  {
    RecordingWriter w((dir / "rec").string(), synth.meta());
    for (int i = 0; i < o.frames; ++i) w.write(synth.render(i));
  }
  SourceOptions sel;
  sel.start = 1;
  sel.every = 3;
  RecordingFrameSource source((dir / "rec").string(), sel);
  EXPECT_EQ(source.frame_count(), 3);  // frames 1, 4, 7
  EXPECT_EQ(source.fps(), 30.0);
  Frame f;
  std::vector<int> seen;
  while (source.read(f)) {
    seen.push_back(f.index);
    EXPECT_EQ(f.image.size(), cv::Size(160, 90));
    EXPECT_DOUBLE_EQ(f.time_s, f.index / 30.0);
  }
  EXPECT_EQ(seen, (std::vector<int>{1, 4, 7}));
  EXPECT_EQ(cv::norm(synth.render(4).color, RecordingReader((dir / "rec").string()).read_frame(4).color, cv::NORM_INF), 0.0);
}

TEST(RecordingFrameSource, RefusesARecordingWithoutColour) {
  TempDir dir;
  RecordingMeta m;
  m.depth = m.color = kinect2_depth_intrinsics();
  m.streams.bodies = true;
  { RecordingWriter w((dir / "rec").string(), m); }
  EXPECT_TRUE(contains(input_error([&] { RecordingFrameSource((dir / "rec").string()); }), "recording has no colour stream"));
}

}  // namespace
}  // namespace bodyrec
