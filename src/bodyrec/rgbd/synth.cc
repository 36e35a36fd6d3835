#include "bodyrec/rgbd/synth.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/rgbd/synth_render.h"

namespace bodyrec {
namespace {

using synth::uniform;

constexpr double kCameraHeight = 1.0;  // metres above the floor, looking horizontally
constexpr double kPi = 3.14159265358979323846;

double deg(double rad) { return rad * 180.0 / kPi; }
double rad(double d) { return d * kPi / 180.0; }

// Yaw (degrees) that faces along (dx, dz): forward = (-sin yaw, -cos yaw).
double yaw_towards(double dx, double dz) { return deg(std::atan2(-dx, -dz)); }

// A person's script: piecewise-linear position and yaw over normalised time 0..1.
struct Segment {
  double t0, t1, x0, z0, x1, z1, yaw0, yaw1;  // yaw in degrees, unwrapped (a turn may exceed 360)
  double stride;                              // gait amplitude during the segment
};

class Script {
 public:
  Script(double x, double z, double yaw) : x_(x), z_(z), yaw_(yaw) {}
  Script& walk_to(double x, double z, double t1) {
    const double yaw = unwrap_near(yaw_towards(x - x_, z - z_));
    add(t1, x, z, yaw, yaw, 1.0);
    return *this;
  }
  Script& turn_by(double degrees, double t1) { return add(t1, x_, z_, yaw_, yaw_ + degrees, 0.35); }
  Script& face(double yaw, double t1) { return add(t1, x_, z_, yaw_, unwrap_near(yaw), 0.3); }
  Script& wait(double t1) { return add(t1, x_, z_, yaw_, yaw_, 0.0); }
  const std::vector<Segment>& segments() const { return segs_; }

 private:
  Script& add(double t1, double x, double z, double yaw0, double yaw1, double stride) {
    segs_.push_back({t_, t1, x_, z_, x, z, yaw0, yaw1, stride});
    t_ = t1, x_ = x, z_ = z, yaw_ = yaw1;
    return *this;
  }
  double unwrap_near(double yaw) const {
    while (yaw - yaw_ > 180) yaw -= 360;
    while (yaw - yaw_ < -180) yaw += 360;
    return yaw;
  }
  double t_ = 0, x_, z_, yaw_;
  std::vector<Segment> segs_;
};

// Pose at normalised time t (gait phase from the distance walked and the angle turned so far).
synth::Pose pose_at(const Script& s, double t, double height) {
  synth::Pose p;
  const auto& segs = s.segments();
  double travelled = 0;
  const Segment* cur = &segs.front();
  double f = 0;
  for (const Segment& g : segs) {
    const double len = std::hypot(g.x1 - g.x0, g.z1 - g.z0) + 0.25 * std::abs(rad(g.yaw1 - g.yaw0));
    cur = &g;
    if (t < g.t0) {
      f = 0;
      break;
    }
    if (t <= g.t1) {
      f = g.t1 > g.t0 ? (t - g.t0) / (g.t1 - g.t0) : 1.0;
      travelled += len * f;
      break;
    }
    travelled += len;
    f = 1;
  }
  const double x = cur->x0 + (cur->x1 - cur->x0) * f, z = cur->z0 + (cur->z1 - cur->z0) * f;
  double yaw = cur->yaw0 + (cur->yaw1 - cur->yaw0) * f;
  yaw = std::remainder(yaw, 360.0);
  p.floor_point = {x, -kCameraHeight, z};
  p.yaw = rad(yaw);
  p.stride = (f > 0 && f < 1) ? cur->stride : 0.0;
  p.phase = 2 * kPi * travelled / (0.85 * height);
  return p;
}

// Horizontal distance from the optical axis at which someone at depth z is well out of view.
double outside(double z) { return 0.72 * z + 0.7; }

// "visits": every person comes twice. Visit k of the 2n (in a seeded order) starts at k * step and lasts
// `overlap` steps, so that about that many visits are under way at any time. A visit: in from one side,
// walk to a spot, turn round once, out on the other side. The second visit comes in from the side the first
// left by, in another lane (lanes go by visit order, so visits under way at once never share one).
double visits_overlap(int people) { return std::min(3.5, people - 0.5); }

std::vector<Script> make_visits(const SynthOptions& o) {
  const int n = o.people;
  const double overlap = visits_overlap(n), step = 1.0 / (2 * n - 1 + overlap), length = overlap * step;
  const int lanes = n % 5 == 0 ? 4 : 5;
  const auto lane = [&](int k) { return 2.2 + 0.5 * (k % lanes); };
  // second[i]: person i's place in the second round. The identity always keeps a person's two visits apart
  // (a gap of n - overlap >= 0.5 steps) and in different lanes (n % lanes != 0); seeded shuffles that do
  // too are preferred, so the order of returns differs from the order of first visits.
  std::vector<int> second(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) second[static_cast<size_t>(i)] = i;
  for (uint64_t attempt = 0; attempt < 64; ++attempt) {
    std::vector<int> p = second;
    for (int i = n - 1; i > 0; --i)
      std::swap(p[static_cast<size_t>(i)], p[static_cast<size_t>(uniform(o.seed, 600 + attempt, static_cast<uint64_t>(i)) * (i + 1))]);
    bool ok = true;
    for (int i = 0; i < n && ok; ++i) {
      const int k = n + p[static_cast<size_t>(i)];
      ok = k - i >= overlap + 0.5 && k % lanes != i % lanes;
    }
    if (ok) {
      second = p;
      break;
    }
  }
  std::vector<Script> scripts;
  for (int i = 0; i < n; ++i) {
    const auto u = [&](int k) { return uniform(o.seed, 700 + static_cast<uint64_t>(i), static_cast<uint64_t>(k)); };
    double side = (i % 2 == 0) ? -1 : 1;  // -1 enters from the left (small u)
    const int first = i, again = n + second[static_cast<size_t>(i)];
    Script s(side * outside(lane(first)), lane(first), 0);
    for (int k : {first, again}) {
      const double z = lane(k), t0 = k * step;
      const double spot = 0.7 * (2 * u(2 * k) - 1), turn = u(2 * k + 1) < 0.5 ? 360 : -360;
      if (k == first)
        s.wait(t0);
      else
        s.walk_to(side * outside(z), z, t0);  // out of view: over to this visit's lane
      s.walk_to(spot, z, t0 + 0.4 * length).turn_by(turn, t0 + 0.7 * length).walk_to(-side * outside(z), z, t0 + length);
      side = -side;
    }
    scripts.push_back(s);
  }
  return scripts;
}

std::vector<Script> make_scripts(const SynthOptions& o) {
  if (o.scenario == "visits") return make_visits(o);
  std::vector<Script> scripts;
  const int n = o.people;
  const auto u = [&](int i, int k) { return uniform(o.seed, 500 + static_cast<uint64_t>(i), static_cast<uint64_t>(k)); };
  // Everyone walks across in a lane (depth) of their own, at least 0.44 m from the next, so that people
  // pass in front of each other instead of through each other. Lanes are shuffled by the seed.
  std::vector<int> lane_of(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) lane_of[static_cast<size_t>(i)] = i;
  for (int i = n - 1; i > 0; --i)
    std::swap(lane_of[static_cast<size_t>(i)], lane_of[static_cast<size_t>(uniform(o.seed, 88, static_cast<uint64_t>(i)) * (i + 1))]);
  // Up to 6 people share 2.3..4.5 m; more keep 0.4 m apart and reach further back.
  const double spacing = n > 6 ? 0.4 : n > 1 ? std::min(0.8, 2.2 / (n - 1)) : 0.0;
  const auto lane = [&](int i) { return 2.3 + spacing * lane_of[static_cast<size_t>(i) % lane_of.size()]; };
  for (int i = 0; i < n; ++i) {
    const double side = (i % 2 == 0) ? -1 : 1;  // -1 enters from the left (small u)
    const double lag = 0.04 * i;
    const double z = lane(i);
    const double spot = (n == 1 ? 0.0 : (i - (n - 1) / 2.0) * (1.6 / n)) + 0.2 * (u(i, 1) - 0.5);
    const double turn = u(i, 2) < 0.5 ? 360 : -360;
    if (o.scenario == "walk-turn") {
      Script s(side * outside(z), z, 0);
      s.wait(lag).walk_to(spot, z, 0.3 + lag).turn_by(turn, 0.7).walk_to(-side * outside(z), z, 1.0);
      scripts.push_back(s);
    } else if (o.scenario == "cross") {
      Script s(side * outside(z), z, 0);
      s.wait(lag).walk_to(-side * outside(z), z, 0.45 + lag).turn_by(180 * side, 0.55 + lag).walk_to(side * outside(z), z, 1.0);
      scripts.push_back(s);
    } else if (o.scenario == "group") {
      const double dx = (i - (n - 1) / 2.0) * 0.62, dz = (i % 2) * 0.3 + 0.1 * u(i, 0);
      const double cx = 0.0, cz = 2.9;
      Script s(-4.0 + dx, cz + dz, 0);
      s.walk_to(cx + dx, cz + dz, 0.35);
      s.face(yaw_towards(cx - (cx + dx), cz + 0.15 - (cz + dz)), 0.42).wait(0.62);
      s.walk_to(3.0 + dx, 4.0 + dz, 1.0);
      scripts.push_back(s);
    } else {  // reenter: in, look around, out, away for a while, back in another lane, turn round
      Script s(side * outside(z), z, 0);
      const double z2 = lane(i + 1);
      s.wait(lag).walk_to(spot, z, 0.2 + lag).turn_by(180, 0.3 + lag).walk_to(side * outside(z), z, 0.45 + lag);
      // Out of view: further out, over to the new lane there, back to the edge.
      s.walk_to(side * (outside(z) + 1.2), z, 0.49 + lag).walk_to(side * (outside(z2) + 1.2), z2, 0.52 + lag);
      s.walk_to(side * outside(z2), z2, 0.55 + lag);
      s.walk_to(-spot * 0.8, z2, 0.75 + lag / 2).turn_by(turn, 1.0);
      scripts.push_back(s);
    }
  }
  return scripts;
}

}  // namespace

void SynthOptions::check() const {
  const auto fail = [](const char* field, const std::string& problem) { throw OptionError("SynthOptions", field, problem); };
  if (people < 1 || people > kMaxSynthPeople)
    fail("people", "must be 1..8 (at most 6 are tracked at once, like a Kinect)");
  if (frames < 1) fail("frames", "must be positive");
  const auto& s = synth_scenarios();
  if (std::find(s.begin(), s.end(), scenario) == s.end())
    fail("scenario", "\"" + scenario + "\" is unknown (walk-turn, cross, group, reenter, visits)");
  if (color_width < 64 || color_width > 4096) fail("color_width", "must be 64..4096");
  if (color_height < 48 || color_height > 4096) fail("color_height", "must be 48..4096");
}

const std::vector<std::string>& synth_scenarios() {
  static const std::vector<std::string> s = {"walk-turn", "cross", "group", "reenter", "visits"};
  return s;
}

int synth_recommended_frames(const std::string& scenario, int people) {
  if (scenario != "visits") return 150;
  // 150 frames (5 s) per visit; the recording spans (2 people - 1 + overlap) / overlap visit lengths.
  const double overlap = visits_overlap(people);
  return static_cast<int>(std::ceil(150 * (2 * people - 1 + overlap) / overlap / 10)) * 10;
}

struct Synthesizer::Impl {
  SynthOptions options;
  RecordingMeta meta;
  std::vector<synth::Look> looks;
  std::vector<Script> scripts;
  cv::Mat room_depth_z, room_color_z, room_color;
  synth::Target depth_target, color_target;
  std::vector<cv::Mat> coverage;

  double time_of(int index) const { return options.frames > 1 ? static_cast<double>(index) / (options.frames - 1) : 0.0; }

  // [person][frame], worked out once: the body-index slot (-1: none), and how many times the person has
  // been tracked so far (negative while not tracked); tracking ids follow the count.
  std::vector<std::vector<int>> slots, entries;

  synth::Pose pose(int i, int index) const {
    return pose_at(scripts[static_cast<size_t>(i)], time_of(index), looks[static_cast<size_t>(i)].height);
  }
  // Whether person i's SpineBase is inside the depth image at frame `index` (Kinect tracks the body then).
  bool in_view(int i, int index) const {
    const cv::Vec3d pelvis = pose(i, index).floor_point + cv::Vec3d(0, 0.53 * looks[static_cast<size_t>(i)].height, 0);
    const auto px = project(meta.depth, pelvis);
    return px && px->x >= 0 && px->x < meta.depth.width;
  }

  // Slots: a person takes the lowest free one when any part of them may show in the depth image (or the
  // pelvis is in it) and keeps it until wholly out; people waiting for a slot are served in identity order.
  // Tracked = pelvis in view and holding a slot; each start of being tracked is a new entry (tracking id).
  void assign_slots() {
    const size_t n = static_cast<size_t>(options.people);
    slots.assign(n, std::vector<int>(static_cast<size_t>(options.frames), -1));
    entries = slots;
    std::vector<int> slot(n, -1), count(n, 0);
    std::vector<bool> was_tracked(n, false), view(n), present(n);
    for (int k = 0; k < options.frames; ++k) {
      std::vector<bool> taken(kMaxBodies, false);
      for (size_t i = 0; i < n; ++i) {
        const int p = static_cast<int>(i);
        view[i] = in_view(p, k);
        present[i] = view[i] || synth::may_cover_image(synth::build_person(looks[i], pose(p, k)), meta.depth);
        if (!present[i]) slot[i] = -1;
        if (slot[i] >= 0) taken[static_cast<size_t>(slot[i])] = true;
      }
      for (size_t i = 0; i < n; ++i) {
        for (size_t free = 0; present[i] && slot[i] < 0 && free < taken.size(); ++free)
          if (!taken[free]) {
            taken[free] = true;
            slot[i] = static_cast<int>(free);
          }
        const bool tracked = view[i] && slot[i] >= 0;
        if (tracked && !was_tracked[i]) ++count[i];
        was_tracked[i] = tracked;
        slots[i][static_cast<size_t>(k)] = slot[i];
        entries[i][static_cast<size_t>(k)] = tracked ? count[i] : -count[i];
      }
    }
  }
};

Synthesizer::Synthesizer(const SynthOptions& options) : impl_(std::make_unique<Impl>()) {
  options.check();
  Impl& m = *impl_;
  m.options = options;
  m.meta.sensor = "bodyrec synth (" + options.scenario + ", " + std::to_string(options.people) + " people, seed " +
                  std::to_string(options.seed) +
                  (options.looks_seed ? ", looks seed " + std::to_string(*options.looks_seed) : std::string()) + ")";
  m.meta.fps = 30;
  m.meta.depth = kinect2_depth_intrinsics();
  m.meta.color = scaled(kinect2_color_intrinsics(), options.color_width, options.color_height);
  m.meta.depth_to_color = kinect2_depth_to_color();
  m.meta.streams = {true, true, true, true, true};
  for (int i = 0; i < options.people; ++i) m.looks.push_back(synth::make_look(options.looks_seed.value_or(options.seed), i, options.people));
  m.scripts = make_scripts(options);
  m.assign_slots();
  const cv::Vec3d t = m.meta.depth_to_color.translation;
  m.color_target.k = m.meta.color;
  m.color_target.offset = cv::Vec3f(t);
  m.color_target.color.create(m.meta.color.height, m.meta.color.width, CV_8UC3);
  synth::draw_room(m.color_target, kCameraHeight);
  m.room_color_z = m.color_target.z.clone();
  m.room_color = m.color_target.color.clone();
  m.depth_target.k = m.meta.depth;
  m.depth_target.pad = 256;
  synth::draw_room(m.depth_target, kCameraHeight);
  m.room_depth_z = m.depth_target.z.clone();
  m.depth_target.label.create(m.meta.depth.height, m.meta.depth.width, CV_8U);
}

Synthesizer::~Synthesizer() = default;

const RecordingMeta& Synthesizer::meta() const { return impl_->meta; }

RgbdFrame Synthesizer::render(int index) {
  Impl& m = *impl_;
  const SynthOptions& o = m.options;
  CV_Assert(index >= 0 && index < o.frames);
  const int n = o.people, w = m.meta.depth.width, h = m.meta.depth.height;
  RgbdFrame f;
  f.index = index;
  f.time_s = index / m.meta.fps;

  std::vector<synth::PersonModel> models;
  for (int i = 0; i < n; ++i)
    models.push_back(synth::build_person(m.looks[static_cast<size_t>(i)], m.pose(i, index)));

  // Depth camera: z, labels (identities) and coverage (for the visible fraction).
  synth::Target& dt = m.depth_target;
  m.room_depth_z.copyTo(dt.z);
  dt.label.setTo(kNoBody);
  m.coverage.resize(static_cast<size_t>(n));
  std::vector<int> covered(static_cast<size_t>(n), 0);
  for (int i = 0; i < n; ++i) {
    cv::Mat& c = m.coverage[static_cast<size_t>(i)];
    c.create(h + 2 * dt.pad, w + 2 * dt.pad, CV_8U);
    c.setTo(0);
    synth::draw_person(m.looks[static_cast<size_t>(i)], models[static_cast<size_t>(i)], i, dt, &c);
    covered[static_cast<size_t>(i)] = cv::countNonZero(c);
  }
  // Colour camera.
  synth::Target& ct = m.color_target;
  m.room_color_z.copyTo(ct.z);
  m.room_color.copyTo(ct.color);
  for (int i = 0; i < n; ++i) synth::draw_person(m.looks[static_cast<size_t>(i)], models[static_cast<size_t>(i)], i, ct, nullptr);
  f.color = ct.color.clone();

  // Sensor effects: noise growing with distance (sigma 1 mm + 0.6 mm m^-2 z^2), dropouts far away, at
  // depth edges (mixed pixels) and in the dark corners of a Kinect v2 depth image; no body where no depth.
  f.depth.create(h, w, CV_16U);
  cv::Mat people = dt.label.clone();  // identity per pixel; the body index shows slots
  const uint64_t frame_key = (o.seed << 20) ^ static_cast<uint64_t>(index);
  for (int v = 0; v < h; ++v) {
    const float* z = dt.z.ptr<float>(v);
    const float* below = dt.z.ptr<float>(std::min(v + 1, h - 1));
    uint16_t* out = f.depth.ptr<uint16_t>(v);
    uint8_t* label = people.ptr<uint8_t>(v);
    const double ry = (v - m.meta.depth.cy) / (h / 2.0);
    for (int u = 0; u < w; ++u) {
      const uint32_t r = synth::hash32(frame_key * 0x9E3779B97F4A7C15ULL + static_cast<uint64_t>(v * w + u));
      const float zz = z[u];
      const double rx = (u - m.meta.depth.cx) / (w / 2.0);
      const float edge = std::max(std::abs(z[std::min(u + 1, w - 1)] - zz), std::abs(below[u] - zz));
      const double p_drop = 0.002 + (zz > 4.5f ? 0.08 * (zz - 4.5) : 0.0) + (edge > 0.08f ? 0.55 : 0.0);
      const bool corner = rx * rx + ry * ry > 1.8;
      if (corner || zz > 8.0f || zz < 0.5f || (r & 0xffff) < p_drop * 65536) {
        out[u] = 0;
        label[u] = kNoBody;
        continue;
      }
      const double gauss = (((r >> 16) & 0xff) + ((r >> 24) & 0xff) + ((r >> 8) & 0xff) - 382.5) / 127.7;  // ~N(0, 1)
      const double sigma = 0.001 + 0.0006 * zz * zz;
      out[u] = static_cast<uint16_t>(std::lround((zz + gauss * sigma) * 1000.0));
    }
  }

  cv::Mat slot_of(1, 256, CV_8U, cv::Scalar(kNoBody));  // untracked people stay out of the body index
  for (int i = 0; i < n; ++i) {
    const int slot = m.slots[static_cast<size_t>(i)][static_cast<size_t>(index)];
    if (slot >= 0) slot_of.at<uint8_t>(i) = static_cast<uint8_t>(slot);
  }
  cv::LUT(people, slot_of, f.body_index);

  // Bodies and truth.
  FrameTruth truth;
  for (int i = 0; i < n; ++i) {
    const synth::Look& look = m.looks[static_cast<size_t>(i)];
    const synth::PersonModel& model = models[static_cast<size_t>(i)];
    const int entry = m.entries[static_cast<size_t>(i)][static_cast<size_t>(index)];
    const bool was = entry > 0;
    const int entries = std::abs(entry);
    PersonTruth t;
    t.identity = i;
    t.tracking_id = static_cast<uint64_t>(1000 + 100 * i + std::max(entries, 1) - 1);
    const int slot = m.slots[static_cast<size_t>(i)][static_cast<size_t>(index)];
    const cv::Mat mine = people == i;
    t.visible_pixels = cv::countNonZero(mine);
    t.depth_box = t.visible_pixels ? cv::boundingRect(mine) : cv::Rect();
    t.visible_fraction = covered[static_cast<size_t>(i)] ? std::min(1.0, static_cast<double>(t.visible_pixels) / covered[static_cast<size_t>(i)]) : 0.0;
    t.body_index = (was && t.visible_pixels > 0) ? slot : -1;
    const cv::Matx33d& r = model.body_to_camera;  // forward = R (0, 0, -1) = (-r02, -r22)
    t.yaw_deg = yaw_towards(-r(0, 2), -r(2, 2));
    if (t.yaw_deg <= -180) t.yaw_deg += 360;
    t.position = model.joints[idx(Joint::kSpineBase)];
    t.height_m = look.height;
    t.top = look.top_text;
    t.bottom = look.bottom_text;
    t.accessories = look.accessories;
    t.top_bgr = cv::Vec3b(look.top);
    t.bottom_bgr = cv::Vec3b(look.bottom);
    truth.people.push_back(t);
    if (t.body_index < 0 || t.visible_pixels < 100) continue;  // Kinect would not track this body
    Body body;
    body.tracking_id = t.tracking_id;
    body.index = slot;
    for (int j = 0; j < kJointCount; ++j) {
      BodyJoint& bj = body.joints[static_cast<size_t>(j)];
      bj.position = model.joints[static_cast<size_t>(j)];
      bj.orientation = model.orientations[static_cast<size_t>(j)];
      const auto px = project(m.meta.depth, bj.position);
      const int pu = px ? static_cast<int>(std::lround(px->x)) : -1, pv = px ? static_cast<int>(std::lround(px->y)) : -1;
      const bool inside = pu >= 0 && pu < w && pv >= 0 && pv < h;
      // Tracked when the joint's pixel shows this body near the joint's depth, inferred otherwise.
      bj.tracking_state = !inside ? 0 : (people.at<uint8_t>(pv, pu) == i || std::abs(dt.z.at<float>(pv, pu) - bj.position[2]) < 0.15) ? 2 : 1;
    }
    f.bodies.push_back(body);
  }
  f.truth = truth;
  return f;
}

}  // namespace bodyrec
