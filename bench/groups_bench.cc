// Cost of one GroupMembership::update (pair features for every pair seen, model, regrouping) with N people
// walking in pairs and alone at the tracker's 7 fps, after the 8 s window has filled.
#include <cmath>
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

void BM_GroupMembershipUpdate(benchmark::State& state) {
  const int people = static_cast<int>(state.range(0));
  bodyrec::GroupMembership groups;
  double t = 0;
  for (int k = 0; k < 70; ++k, t += 1.0 / 7) groups.update(t, crowd(people, t));  // fill the window
  for (auto _ : state) {
    groups.update(t, crowd(people, t));
    t += 1.0 / 7;
  }
  state.counters["groups"] = static_cast<double>(groups.groups().size());
}
BENCHMARK(BM_GroupMembershipUpdate)->Arg(10)->Arg(20)->Arg(40)->Unit(benchmark::kMicrosecond)->MinTime(2.0);

}  // namespace

BENCHMARK_MAIN();
