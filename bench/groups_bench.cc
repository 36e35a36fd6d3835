// Cost of one GroupMembership::update (pair features for every pair seen, model, regrouping) with N people
// walking in pairs and alone at the tracker's 7 fps, after H seconds of history. The default model looks
// at a pair's whole common time (at most max_history_s, 120 s), so its cost grows with H up to that.
#include <cmath>
#include <memory>
#include <vector>

#include <benchmark/benchmark.h>

#include "bodyrec/groups/group_membership.h"

namespace {

std::vector<std::pair<int, cv::Point2d>> crowd(int people, double t) {
  std::vector<std::pair<int, cv::Point2d>> positions;
  for (int id = 0; id < people; ++id) {
    const int pair = id / 2;  // people 2k and 2k+1 walk together
    const double heading = 0.7 * pair, speed = 1.0 + 0.05 * (pair % 5);
    const cv::Point2d start(3.0 * (pair % 6), 3.0 * (pair / 6));
    positions.emplace_back(id, start + cv::Point2d(std::cos(heading), std::sin(heading)) * speed * t +
                                   cv::Point2d(0.0, 0.6 * (id % 2)));
  }
  return positions;
}

// Args: people, seconds of history before the timed update.
void BM_GroupMembershipUpdate(benchmark::State& state) {
  const int people = static_cast<int>(state.range(0));
  const double history = static_cast<double>(state.range(1));
  bodyrec::GroupMembership filled;
  double t = 0;
  for (; t < history; t += 1.0 / 7) filled.update(t, crowd(people, t));
  const auto next = crowd(people, t);
  std::unique_ptr<bodyrec::GroupMembership> groups;
  for (auto _ : state) {
    state.PauseTiming();
    groups = std::make_unique<bodyrec::GroupMembership>(filled);  // the same history every time
    state.ResumeTiming();
    groups->update(t, next);
  }
  state.counters["groups"] = static_cast<double>(filled.groups().size());
}
BENCHMARK(BM_GroupMembershipUpdate)
    ->ArgsProduct({{10, 20, 40}, {10, 60, 120}})
    ->Unit(benchmark::kMicrosecond)
    ->MinTime(1.0);

}  // namespace

BENCHMARK_MAIN();
