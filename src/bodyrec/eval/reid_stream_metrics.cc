#include "bodyrec/eval/reid_stream_metrics.h"

#include <algorithm>
#include <tuple>
#include <vector>

#include "bodyrec/tracking/assignment.h"

namespace bodyrec {

std::vector<int> match_bodies_to_truth(const std::vector<Box>& bodies, const std::vector<Box>& truth, double min_iou) {
  std::vector<std::vector<double>> overlap(bodies.size(), std::vector<double>(truth.size()));
  for (size_t b = 0; b < bodies.size(); ++b)
    for (size_t t = 0; t < truth.size(); ++t) overlap[b][t] = iou(bodies[b], truth[t]);
  std::vector<int> match(bodies.size(), -1);
  for (const auto& [b, t] : max_score_assignment(overlap, min_iou)) match[static_cast<size_t>(b)] = t;
  return match;
}
namespace {

template <typename K>
K majority(const std::map<K, int>& counts) {
  K best{};
  int most = -1;
  for (const auto& [k, n] : counts)
    if (n > most) best = k, most = n;
  return best;
}

}  // namespace

void ReidStreamCounter::add(int identity, uint64_t track, std::optional<int64_t> user) {
  ++frames_;
  identities_.insert(identity);
  TrackStats& t = tracks_[track];
  ++t.identities[identity];
  if (!user) {
    ++undecided_;
    return;
  }
  t.user = user;
  ++user_frames_[*user][identity];
}

void ReidStreamCounter::assign(uint64_t track, int64_t user) {
  const auto it = tracks_.find(track);
  if (it != tracks_.end()) it->second.user = user;  // tracks never seen with a true person stay out
}

ReidStreamScore ReidStreamCounter::score() const {
  ReidStreamScore s;
  s.frames = frames_;
  s.undecided = undecided_;
  s.identities = static_cast<int>(identities_.size());
  s.users = static_cast<int>(user_frames_.size());
  // One user per identity and one identity per user, chosen greedily by shared body-frames: the frames
  // of a second user for one person (a split) or of a second person under one user (a merge) are wrong.
  std::vector<std::tuple<int, int64_t, int>> pairs;  // frames, user, identity
  for (const auto& [user, counts] : user_frames_)
    for (const auto& [identity, n] : counts) pairs.emplace_back(n, user, identity);
  std::sort(pairs.begin(), pairs.end(), [](const auto& a, const auto& b) { return std::get<0>(a) > std::get<0>(b); });
  std::set<int64_t> used_users;
  std::set<int> used_identities;
  for (const auto& [n, user, identity] : pairs)
    if (!used_users.count(user) && !used_identities.count(identity)) {
      used_users.insert(user);
      used_identities.insert(identity);
      s.correct += n;
    }
  s.accuracy = frames_ ? static_cast<double>(s.correct) / frames_ : 0.0;
  std::map<int, std::set<int64_t>> users_of_identity;
  std::map<int64_t, std::set<int>> identities_of_user;
  for (const auto& [key, t] : tracks_) {
    if (!t.user) continue;
    ++s.tracks;
    const int identity = majority(t.identities);
    users_of_identity[identity].insert(*t.user);
    identities_of_user[*t.user].insert(identity);
  }
  for (const auto& [i, users] : users_of_identity) s.splits += static_cast<int>(users.size()) - 1;
  for (const auto& [u, ids] : identities_of_user) s.merges += static_cast<int>(ids.size()) - 1;
  return s;
}

}  // namespace bodyrec
