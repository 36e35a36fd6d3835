#include "bodyrec/groups/group_membership.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>
#include <string>
#include <tuple>

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace {

std::pair<int, int> key(int a, int b) { return a < b ? std::make_pair(a, b) : std::make_pair(b, a); }

void require_positive(double v, const char* name) {
  if (!(v > 0) || !std::isfinite(v))
    throw OptionError("GroupOptions", name, "must be a positive number, got " + std::to_string(v));
}

}  // namespace

void GroupOptions::check() const {
  if (!(window_s > 0)) throw OptionError("GroupOptions", "window_s", "must be > 0, got " + std::to_string(window_s));
  require_positive(velocity_span_s, "velocity_span_s");
  require_positive(max_history_s, "max_history_s");
  require_positive(units_per_metre, "units_per_metre");
  require_positive(forget_after_s, "forget_after_s");
  if (!(evidence_half_life_s >= 0) || !std::isfinite(evidence_half_life_s))
    throw OptionError("GroupOptions", "evidence_half_life_s", "must be >= 0, got " + std::to_string(evidence_half_life_s));
  if (!(min_moving_fraction >= 0 && min_moving_fraction <= 1))
    throw OptionError("GroupOptions", "min_moving_fraction", "must be in [0, 1], got " + std::to_string(min_moving_fraction));
}

GroupOptions options_for(std::shared_ptr<const PairModel> model, GroupOptions base) {
  if (!model) throw UsageError("group options: no model given");
  base.window_s = model->window_s;
  base.velocity_span_s = model->velocity_span_s;
  base.min_moving_fraction = model->min_moving_fraction;
  base.linkage = model->linkage;
  base.model = std::move(model);
  return base;
}

GroupMembership::GroupMembership(GroupOptions options) : options_(std::move(options)) {
  options_.check();
  model_ = options_.model;
  if (!model_) model_ = std::make_shared<const PairModel>(builtin_pair_model_for(""));
}

void GroupMembership::update(double t, const std::vector<std::pair<int, cv::Point2d>>& positions) {
  if (!std::isfinite(t)) throw UsageError("group membership: time is not finite");
  if (step_ > 0 && !(t > last_t_))
    throw UsageError("group membership: time " + std::to_string(t) + " s is not after the previous update (" +
                     std::to_string(last_t_) + " s)");
  std::vector<int> present;
  for (const auto& [id, position] : positions) present.push_back(id);
  std::sort(present.begin(), present.end());
  if (std::adjacent_find(present.begin(), present.end()) != present.end())
    throw UsageError("group membership: a track id is listed twice at time " + std::to_string(t) + " s");
  ++step_;
  last_t_ = t;
  for (const auto& [id, position] : positions) {
    if (!std::isfinite(position.x) || !std::isfinite(position.y))
      throw UsageError("group membership: track " + std::to_string(id) + " has a non-finite position");
    PersonHistory& h = people_[id];
    h.add(step_, t, position / options_.units_per_metre, options_.velocity_span_s);
    h.drop_before(t - span());
  }
  std::vector<int> gone;
  for (const auto& [id, history] : people_)
    if (history.last_seen() < t - options_.forget_after_s) gone.push_back(id);
  for (int id : gone) drop(id);

  const bool whole_time = std::isinf(options_.window_s);  // the latest window replaces the evidence
  // A rule over the whole common time needs only running medians (pair_features would cost time in
  // proportion to the history).
  const bool running = whole_time && model_->rule;
  const double decay_rate = options_.evidence_half_life_s > 0 ? std::log(2.0) / options_.evidence_half_life_s : 0;
  for (size_t i = 0; i < present.size(); ++i) {
    for (size_t j = i + 1; j < present.size(); ++j) {
      std::optional<PairFeatures> f;
      if (running) {
        const PersonSample& a = people_[present[i]].samples().back();
        const PersonSample& b = people_[present[j]].samples().back();
        RunningPairStatistics& r = running_[{present[i], present[j]}];
        if (a.has_velocity && b.has_velocity) r.add(a, b, span());
        f = r.features();
      } else {
        f = pair_features(people_[present[i]], people_[present[j]], t, span());
      }
      if (!f || !counts(*f)) continue;
      Evidence& e = evidence_[{present[i], present[j]}];
      const double keep = whole_time || !(e.weight > 0) ? 0.0 : std::exp(-decay_rate * (t - e.last_t));
      e.sum = keep * e.sum + model_->logit(f->values);
      e.weight = keep * e.weight + 1;
      e.last_t = t;
    }
  }
  regroup();
}

void GroupMembership::regroup() {
  std::vector<int> ids = people();
  std::map<std::pair<int, int>, double> mean;
  for (const auto& [pair, e] : evidence_) mean[pair] = e.sum / e.weight;
  std::vector<std::vector<int>> clusters;
  for (auto& c : cluster_pairs(ids, mean, options_.linkage))
    if (c.size() >= 2) clusters.push_back(std::move(c));

  // Stable ids: greedily give each old group id to the new cluster that shares most members with it.
  std::vector<std::tuple<int, int, size_t>> overlaps;  // (-shared members, old id, cluster index)
  for (size_t c = 0; c < clusters.size(); ++c) {
    std::map<int, int> shared;
    for (int id : clusters[c]) {
      const auto it = group_of_.find(id);
      if (it != group_of_.end()) ++shared[it->second];
    }
    for (const auto& [old_id, count] : shared) overlaps.emplace_back(-count, old_id, c);
  }
  std::sort(overlaps.begin(), overlaps.end());
  std::vector<int> cluster_id(clusters.size(), 0);
  std::set<int> used;
  for (const auto& [count, old_id, c] : overlaps)
    if (!cluster_id[c] && !used.count(old_id)) {
      cluster_id[c] = old_id;
      used.insert(old_id);
    }
  group_of_.clear();
  for (size_t c = 0; c < clusters.size(); ++c) {
    if (!cluster_id[c]) cluster_id[c] = next_group_id_++;
    for (int id : clusters[c]) group_of_[id] = cluster_id[c];
  }
}

double GroupMembership::span() const { return std::min(options_.window_s, options_.max_history_s); }

bool GroupMembership::counts(const PairFeatures& f) const {
  return f.moving_fraction >= options_.min_moving_fraction;
}

std::map<int, int> GroupMembership::group_of() const { return group_of_; }

std::vector<std::vector<int>> GroupMembership::groups() const {
  std::map<int, std::vector<int>> by_id;
  for (const auto& [person, group] : group_of_) by_id[group].push_back(person);
  std::vector<std::vector<int>> list;
  for (auto& [group, members] : by_id) list.push_back(std::move(members));
  return list;
}

std::optional<double> GroupMembership::pair_evidence(int a, int b) const {
  const auto it = evidence_.find(key(a, b));
  if (it == evidence_.end()) return std::nullopt;
  return it->second.sum / it->second.weight;
}

double GroupMembership::pair_probability(int a, int b) const {
  const auto e = pair_evidence(a, b);
  return e ? 1 / (1 + std::exp(-*e)) : 0.0;
}

std::optional<PairFeatures> GroupMembership::window_features(int a, int b) const {
  const auto ia = people_.find(a), ib = people_.find(b);
  if (ia == people_.end() || ib == people_.end()) return std::nullopt;
  return pair_features(ia->second, ib->second, last_t_, span());
}

void GroupMembership::forget(int id) {
  drop(id);
  regroup();
}

void GroupMembership::drop(int id) {
  people_.erase(id);
  group_of_.erase(id);
  for (auto it = evidence_.begin(); it != evidence_.end();)
    it = it->first.first == id || it->first.second == id ? evidence_.erase(it) : std::next(it);
  for (auto it = running_.begin(); it != running_.end();)
    it = it->first.first == id || it->first.second == id ? running_.erase(it) : std::next(it);
}

std::vector<int> GroupMembership::people() const {
  std::vector<int> ids;
  for (const auto& [id, history] : people_) ids.push_back(id);
  return ids;
}

std::vector<std::vector<int>> cluster_pairs(const std::vector<int>& ids,
                                            const std::map<std::pair<int, int>, double>& evidence,
                                            GroupLinkage linkage) {
  std::vector<int> sorted = ids;
  std::sort(sorted.begin(), sorted.end());
  sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
  const size_t n = sorted.size();
  std::map<int, size_t> index;
  for (size_t i = 0; i < n; ++i) index[sorted[i]] = i;
  std::vector<std::vector<int>> clusters(n);
  for (size_t i = 0; i < n; ++i) clusters[i] = {sorted[i]};

  if (linkage != GroupLinkage::kAverage) {
    std::vector<size_t> parent(n);
    std::iota(parent.begin(), parent.end(), 0);
    auto root = [&](size_t i) {
      while (parent[i] != i) i = parent[i] = parent[parent[i]];
      return i;
    };
    for (const auto& [pair, value] : evidence) {
      const auto a = index.find(pair.first), b = index.find(pair.second);
      if (value > 0 && a != index.end() && b != index.end()) parent[root(a->second)] = root(b->second);
    }
    std::map<size_t, std::vector<int>> by_root;
    for (size_t i = 0; i < n; ++i) by_root[root(i)].push_back(sorted[i]);
    std::vector<std::vector<int>> out;
    for (auto& [r, members] : by_root) out.push_back(std::move(members));
    std::sort(out.begin(), out.end());
    return out;
  }

  // Average linkage over known pairs: sum and count of evidence between clusters, merged on the fly.
  std::vector<std::map<size_t, std::pair<double, int>>> link(n);
  for (const auto& [pair, value] : evidence) {
    const auto a = index.find(pair.first), b = index.find(pair.second);
    if (a == index.end() || b == index.end() || a->second == b->second) continue;
    link[a->second][b->second] = {value, 1};
    link[b->second][a->second] = {value, 1};
  }
  std::vector<bool> alive(n, true);
  for (;;) {
    double best = 0;
    size_t bi = n, bj = n;
    for (size_t i = 0; i < n; ++i) {
      if (!alive[i]) continue;
      for (const auto& [j, sc] : link[i]) {
        const double m = sc.first / sc.second;
        if (i < j && m > best) {
          best = m;
          bi = i;
          bj = j;
        }
      }
    }
    if (bi == n) break;
    // Merge bj into bi.
    clusters[bi].insert(clusters[bi].end(), clusters[bj].begin(), clusters[bj].end());
    clusters[bj].clear();
    alive[bj] = false;
    for (const auto& [k, sc] : link[bj]) {
      if (k == bi) continue;
      auto& to = link[bi][k];
      to.first += sc.first;
      to.second += sc.second;
      link[k][bi] = to;
      link[k].erase(bj);
    }
    link[bi].erase(bj);
    link[bj].clear();
  }
  std::vector<std::vector<int>> out;
  for (size_t i = 0; i < n; ++i)
    if (alive[i]) {
      std::sort(clusters[i].begin(), clusters[i].end());
      out.push_back(clusters[i]);
    }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace bodyrec
