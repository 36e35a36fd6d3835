// Online re-identification of a whole synthetic RGB-D stream through ReidPipeline, in memory: three people
// walk in, out and back in (the `reenter` scenario); each must become one user, recognised when they return.
#include "bodyrec/reid/reid_pipeline.h"

#include <map>
#include <set>

#include <gtest/gtest.h>

#include "bodyrec/core/error.h"
#include "bodyrec/reid/memory_reid_store.h"
#include "bodyrec/rgbd/synth.h"

namespace bodyrec {
namespace {

struct StreamScore {
  int body_frames = 0, right = 0, enrolled = 0, recognised = 0;
  std::map<int, std::set<UserId>> users_of;  // identity -> users it was given
  std::map<UserId, std::set<int>> people_of;  // user -> identities given it
};

StreamScore run(BodySource from, uint64_t seed) {
  SynthOptions so;
  so.people = 3;
  so.seed = seed;
  so.frames = 150;
  so.scenario = "reenter";
  Synthesizer synth(so);
  MemoryReidStore store;
  auto matcher = make_matcher("stripes");
  ReidPipelineOptions po;
  po.orient.bodies.from = from;
  ReidPipeline pipeline(synth.meta(), store, *matcher, po, std::nullopt);
  StreamScore s;
  std::map<int, std::map<UserId, int>> frames_of;  // identity -> user -> body-frames
  for (int i = 0; i < so.frames; ++i) {
    const RgbdFrame f = synth.render(i);
    const ReidResult r = pipeline.process(f);
    EXPECT_EQ(r.bodies.size(), r.step.identities.size());
    for (const ReidEvent& e : r.step.events) {
      s.enrolled += e.kind == ReidEventKind::kEnrolled;
      s.recognised += e.kind == ReidEventKind::kRecognised;
    }
    for (size_t b = 0; b < r.bodies.size(); ++b) {
      if (r.bodies[b].truth < 0) continue;
      const int who = f.truth->people[static_cast<size_t>(r.bodies[b].truth)].identity;
      ++s.body_frames;
      if (const auto user = r.step.identities[b].user) {
        ++frames_of[who][*user];
        s.users_of[who].insert(*user);
        s.people_of[*user].insert(who);
      }
    }
  }
  pipeline.finish();
  for (const auto& [who, users] : frames_of) {
    int most = 0;
    for (const auto& [user, n] : users) most = std::max(most, n);
    s.right += most;
  }
  EXPECT_EQ(store.user_count(), s.enrolled);
  return s;
}

TEST(ReidPipeline, EveryoneIsOneUserAndRecognisedOnReturnWithSkeletons) {
  const StreamScore s = run(BodySource::kSkeleton, 3);
  EXPECT_EQ(s.enrolled, 3);
  EXPECT_GE(s.recognised, 2);  // the people who came back
  for (const auto& [who, users] : s.users_of) EXPECT_EQ(users.size(), 1u) << "person " << who << " split";
  for (const auto& [user, people] : s.people_of) EXPECT_EQ(people.size(), 1u) << "user " << user << " merged";
  ASSERT_GT(s.body_frames, 0);
  EXPECT_GE(static_cast<double>(s.right) / s.body_frames, 0.9) << s.right << " of " << s.body_frames;
}

TEST(ReidPipeline, TheBodyIndexAloneGivesTheSameUsers) {
  const StreamScore s = run(BodySource::kBodyIndex, 3);
  EXPECT_EQ(s.enrolled, 3);
  for (const auto& [who, users] : s.users_of) EXPECT_EQ(users.size(), 1u) << "person " << who << " split";
  for (const auto& [user, people] : s.people_of) EXPECT_EQ(people.size(), 1u) << "user " << user << " merged";
  EXPECT_GE(static_cast<double>(s.right) / s.body_frames, 0.9) << s.right << " of " << s.body_frames;
}

TEST(ReidPipeline, BodiesFromDepthNeedASegmenter) {
  SynthOptions so;
  so.frames = 2;
  Synthesizer synth(so);
  MemoryReidStore store;
  auto matcher = make_matcher("stripes");
  ReidPipelineOptions po;
  po.orient.bodies.from = BodySource::kDepth;
  EXPECT_THROW(ReidPipeline(synth.meta(), store, *matcher, po, std::nullopt), UsageError);
  // A recording without a body index cannot give bodies from it.
  RecordingMeta meta = synth.meta();
  meta.streams.body_index = false;
  po.orient.bodies.from = BodySource::kBodyIndex;
  try {
    ReidPipeline pipeline(meta, store, *matcher, po, std::nullopt, "rec");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("rec: taking bodies from body-index needs a body index stream"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace bodyrec
