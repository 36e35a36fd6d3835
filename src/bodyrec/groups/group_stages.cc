#include "bodyrec/groups/group_stages.h"

#include <algorithm>
#include <chrono>

#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace {

constexpr double kPersonHeightM = 1.7;  // to turn box heights into a pixels-per-metre scale
constexpr int kForgetFrames = 100;      // a track unseen this long is dropped from the role logic

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

cv::Point2d foot(const Box& b) { return {b.x + b.width / 2, b.y + b.height}; }

}  // namespace

const char* to_string(RoleMode mode) {
  switch (mode) {
    case RoleMode::kGroups: return "groups";
    case RoleMode::kThesis: return "thesis";
    case RoleMode::kVoting: return "voting";
  }
  return "?";
}

std::optional<RoleMode> parse_role_mode(const std::string& text) {
  for (RoleMode m : {RoleMode::kGroups, RoleMode::kThesis, RoleMode::kVoting})
    if (text == to_string(m)) return m;
  return std::nullopt;
}

void GroupStagesOptions::check() const {
  if (!(pixels_per_metre >= 0)) throw UsageError("GroupStagesOptions.pixels_per_metre must be >= 0");
  motion.check();
  thesis.check();
  trajectory.check();
  membership.check();
  leader.check();
  direction.check();
}

GroupStages::GroupStages(const GroupStagesOptions& options, std::shared_ptr<const GroundPlane> ground)
    : options_(options), ground_(std::move(ground)), motion_(options.motion), trajectory_(options.trajectory) {
  options_.check();
  if (options_.roles != RoleMode::kGroups) thesis_.emplace(options_.thesis, options_.roles == RoleMode::kVoting);
  pixels_per_metre_ = options_.pixels_per_metre;
}

GroupStages::~GroupStages() = default;

GroupFrame GroupStages::process(const cv::Mat& image, double t, const std::vector<TrackedPerson>& tracks) {
  GroupFrame out;
  auto t0 = Clock::now();
  // One grey conversion per frame, shared by the motion stage, the leader trackers and the flow; the
  // previous frame's buffer is kept by swapping, not copying.
  std::swap(grey_, previous_grey_);
  if (image.channels() == 1) image.copyTo(grey_);
  else cv::cvtColor(image, grey_, cv::COLOR_BGR2GRAY);
  const MotionResult& motion = motion_.update(grey_);
  out.motion_valid = motion.valid;
  out.motion_box = motion.box;
  out.motion_deviation = motion.deviation;
  for (const auto& track : tracks) {
    PersonView p;
    p.id = track.id;
    p.box = track.box;
    p.state = track.state;
    p.motion_energy = motion.energy_in(track.box);
    if (ground_) p.ground = ground_->to_ground(foot(track.box));
    out.people.push_back(p);
    last_seen_[track.id] = frames_;
  }
  std::sort(out.people.begin(), out.people.end(), [](const auto& a, const auto& b) { return a.id < b.id; });
  out.ms.motion = ms_since(t0);

  // Group id -> leader id, including a leader whose track is not reported on this frame: the leader
  // tracker carries it through detector misses.
  const std::map<int, int> leaders = thesis_ ? assign_thesis(out, frames_) : assign_groups(out, t);

  track_leaders(out, tracks, leaders);

  for (auto it = last_seen_.begin(); it != last_seen_.end();) {
    if (frames_ - it->second <= kForgetFrames) {
      ++it;
      continue;
    }
    trajectory_.forget(it->first);
    if (membership_) membership_->forget(it->first);
    it = last_seen_.erase(it);
  }
  ++frames_;
  return out;
}

std::map<int, int> GroupStages::assign_thesis(GroupFrame& out, int frame_index) {
  const auto t0 = Clock::now();
  std::vector<RoleInput> inputs;
  for (const auto& p : out.people) inputs.push_back({p.id, p.box, p.motion_energy});
  const auto roles = thesis_->update(frame_index, inputs, out.motion_box);
  std::vector<PersonView> kept;
  for (auto& p : out.people) {
    const auto it = roles.find(p.id);
    if (it == roles.end()) continue;  // pruned as a still false positive
    p.role = it->second;
    p.group = p.role == Role::kLeader || p.role == Role::kMember ? 1 : -1;
    kept.push_back(p);
  }
  out.people = std::move(kept);
  out.ms.roles = ms_since(t0);
  if (const auto leader = thesis_->leader()) return {{1, *leader}};
  return {};
}

std::map<int, int> GroupStages::assign_groups(GroupFrame& out, double t) {
  auto t0 = Clock::now();
  if (!membership_) {
    if (ground_) {
      pixels_per_metre_ = 1.0;  // positions are already in metres
    } else if (pixels_per_metre_ <= 0) {
      std::vector<double> heights;
      for (const auto& p : out.people) heights.push_back(p.box.height);
      if (heights.empty()) return {};
      std::nth_element(heights.begin(), heights.begin() + heights.size() / 2, heights.end());
      pixels_per_metre_ = heights[heights.size() / 2] / kPersonHeightM;
    }
    GroupOptions o = options_.membership;
    o.units_per_metre = pixels_per_metre_;
    membership_.emplace(o);
  }
  std::vector<std::pair<int, cv::Point2d>> positions;
  for (const auto& p : out.people) positions.emplace_back(p.id, p.ground ? *p.ground : foot(p.box));
  membership_->update(t, positions);
  const auto group_of = membership_->group_of();
  out.ms.groups = ms_since(t0);

  t0 = Clock::now();
  std::vector<TrajectoryInput> inputs;
  for (auto& p : out.people) {
    const auto g = group_of.find(p.id);
    p.group = g == group_of.end() ? -1 : g->second;
    const cv::Point2d where = p.ground ? *p.ground : foot(p.box) * (1.0 / pixels_per_metre_);
    inputs.push_back({p.id, where, p.motion_energy, p.group});
  }
  const auto result = trajectory_.update(t, inputs);
  for (auto& p : out.people) p.role = result.roles.at(p.id);
  out.ms.roles = ms_since(t0);
  return result.leaders;
}

void GroupStages::track_leaders(GroupFrame& out, const std::vector<TrackedPerson>& tracks,
                                  const std::map<int, int>& leaders) {
  for (auto it = leaders_.begin(); it != leaders_.end();)
    it = leaders.count(it->first) ? std::next(it) : leaders_.erase(it);
  for (const auto& [group, leader_id] : leaders) {
    auto t0 = Clock::now();
    auto [it, fresh] = leaders_.try_emplace(group, Leader{LeaderTracker(options_.leader),
                                                          LeaderDirection(options_.direction), -1});
    Leader& leader = it->second;
    LeaderView view;
    view.group = group;
    view.status = leader.tracker.update(grey_, tracks, leader_id);
    if (view.status.handed_over_from) {
      // The leader's track ended and a new track took its place: the new id leads from now on.
      if (thesis_) thesis_->hand_over_leader(*view.status.handed_over_from, view.status.track_id);
      else trajectory_.hand_over_leader(group, view.status.track_id);
      for (auto& p : out.people)
        if (p.id == view.status.track_id) {
          p.role = Role::kLeader;
          p.group = group;
        } else if (p.id == *view.status.handed_over_from) {
          p.role = Role::kMember;
        }
    }
    out.ms.leader += ms_since(t0);

    t0 = Clock::now();
    if (view.status.track_id != leader.last_id || view.status.reacquired) leader.direction.reset();
    leader.last_id = view.status.track_id;
    if (view.status.state == LeaderState::kTracking)
      view.direction = leader.direction.update(previous_grey_, grey_, view.status.box);
    out.ms.flow += ms_since(t0);
    out.leaders.push_back(view);
  }
}

}  // namespace bodyrec
