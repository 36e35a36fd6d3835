#include "bodyrec/rgbd/segment.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>

#include <nlohmann/json.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/rgbd/ground_plane.h"
#include "bodyrec/rgbd/recording.h"

namespace bodyrec {
namespace {

int find_root(std::vector<int>& parent, int i) {
  while (parent[static_cast<size_t>(i)] != i) {
    parent[static_cast<size_t>(i)] = parent[static_cast<size_t>(parent[static_cast<size_t>(i)])];
    i = parent[static_cast<size_t>(i)];
  }
  return i;
}

void unite(std::vector<int>& parent, int a, int b) {
  a = find_root(parent, a);
  b = find_root(parent, b);
  if (a != b) parent[static_cast<size_t>(std::max(a, b))] = std::min(a, b);
}

// Depth jump (metres) below which two neighbouring pixels belong to one surface: a few times the
// quantisation of structured-light / time-of-flight sensors, which grows with z^2.
double max_jump(double z) { return 0.04 + 0.005 * z * z; }

struct Cluster {
  std::vector<int> pixels;  // v * width + u
  double top = -1e9, bottom = 1e9;
  double lat_min = 1e9, lat_max = -1e9, dep_min = 1e9, dep_max = -1e9;
  bool candidate = false;
};

}  // namespace

DepthSegmenter::DepthSegmenter(const Intrinsics& depth_k, double depth_unit_m, SegmentOptions options)
    : k_(depth_k), unit_(depth_unit_m), options_(options) {
  k_.check("segmentation: depth intrinsics");
  if (!(unit_ > 0)) throw InputError("segmentation: depth unit must be positive");
  ray_x_.resize(static_cast<size_t>(k_.width));
  ray_y_.resize(static_cast<size_t>(k_.height));
  for (int u = 0; u < k_.width; ++u) ray_x_[static_cast<size_t>(u)] = static_cast<float>((u - k_.cx) / k_.fx);
  for (int v = 0; v < k_.height; ++v) ray_y_[static_cast<size_t>(v)] = static_cast<float>((k_.cy - v) / k_.fy);
}

static void check_depth(const cv::Mat& depth, const Intrinsics& k) {
  if (depth.type() != CV_16U || depth.cols != k.width || depth.rows != k.height)
    throw InputError("segmentation: depth must be 16-bit " + std::to_string(k.width) + "x" + std::to_string(k.height));
}

void DepthSegmenter::learn_background(const cv::Mat& depth) {
  check_depth(depth, k_);
  if (background_.empty()) {
    background_ = depth.clone();
    return;
  }
  cv::max(background_, depth, background_);
}

std::optional<cv::Vec4d> DepthSegmenter::fit_ground(const cv::Mat& depth) {
  GroundPlaneOptions g;
  g.max_range_m = options_.max_range_m;
  return fit_ground_plane(depth, k_, unit_, g);
}

Segmentation DepthSegmenter::segment(const cv::Mat& depth) {
  check_depth(depth, k_);
  const int w = k_.width, h = k_.height;
  Segmentation out;
  out.labels.create(depth.size(), CV_8U);
  out.labels.setTo(cv::Scalar(kNoBody));

  std::optional<cv::Vec4d> ground = fit_ground(depth);
  if (!ground) ground = last_ground_;
  last_ground_ = ground;
  out.ground = ground;
  const SegmentOptions& o = options_;

  // Ground-plane axes: n up, e1 lateral (camera X projected on the plane), e2 away from the camera.
  cv::Vec3d n(0, 1, 0), e1(1, 0, 0), e2(0, 0, 1);
  double d0 = 0;
  if (ground) {
    n = {(*ground)[0], (*ground)[1], (*ground)[2]};
    d0 = (*ground)[3];
    e1 = cv::Vec3d(1, 0, 0) - n * n[0];
    e1 /= cv::norm(e1);
    e2 = e1.cross(n);
    if (e2[2] < 0) e2 = -e2;
  }

  // With a background model the floor is mostly background already: a thin ground band keeps the feet.
  const double ground_tolerance = background_.empty() ? o.ground_tolerance_m : std::min(0.03, o.ground_tolerance_m);
  // Foreground: valid, in range, not background, not ground. Heights per pixel (NaN = not foreground).
  const size_t npx = static_cast<size_t>(w) * static_cast<size_t>(h);
  std::vector<float> z(npx, 0.f), height(npx, std::nanf(""));
  double lowest = 1e9;
  for (int v = 0; v < h; ++v) {
    const uint16_t* d = depth.ptr<uint16_t>(v);
    const uint16_t* bg = background_.empty() ? nullptr : background_.ptr<uint16_t>(v);
    for (int u = 0; u < w; ++u) {
      if (!d[u]) continue;
      const double zz = d[u] * unit_;
      if (zz > o.max_range_m) continue;
      if (bg && bg[u] && (bg[u] - d[u]) * unit_ < o.background_margin_m + 0.003 * zz * zz) continue;
      const cv::Vec3d p(ray_x_[static_cast<size_t>(u)] * zz, ray_y_[static_cast<size_t>(v)] * zz, zz);
      const double hh = n.dot(p) + d0;
      if (ground && hh < ground_tolerance) continue;
      const size_t i = static_cast<size_t>(v) * static_cast<size_t>(w) + static_cast<size_t>(u);
      z[i] = static_cast<float>(zz);
      height[i] = static_cast<float>(hh);
      lowest = std::min(lowest, hh);
    }
  }
  if (!ground && lowest < 1e9)
    for (auto& x : height) x = static_cast<float>(x - lowest);

  // Connected components of the organised cloud (4-neighbours, depth continuity).
  std::vector<int> parent(npx);
  std::iota(parent.begin(), parent.end(), 0);
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const int i = v * w + u;
      const float zi = z[static_cast<size_t>(i)];
      if (zi == 0.f) continue;
      const double jump = max_jump(zi);
      if (u + 1 < w && z[static_cast<size_t>(i + 1)] != 0.f && std::abs(z[static_cast<size_t>(i + 1)] - zi) < jump)
        unite(parent, i, i + 1);
      if (v + 1 < h && z[static_cast<size_t>(i + w)] != 0.f && std::abs(z[static_cast<size_t>(i + w)] - zi) < jump)
        unite(parent, i, i + w);
    }

  const auto point = [&](int i) {
    const double zz = z[static_cast<size_t>(i)];
    return cv::Vec3d(ray_x_[static_cast<size_t>(i % w)] * zz, ray_y_[static_cast<size_t>(i / w)] * zz, zz);
  };
  // Metric area of a pixel at depth z, to judge cluster sizes independently of distance.
  const double px_area = 1.0 / (k_.fx * k_.fy);
  std::vector<int> cluster_of(npx, -1);
  std::vector<Cluster> clusters;
  std::vector<double> areas;
  for (int i = 0; i < static_cast<int>(npx); ++i) {
    if (z[static_cast<size_t>(i)] == 0.f) continue;
    const int r = find_root(parent, i);
    int& c = cluster_of[static_cast<size_t>(r)];
    if (c < 0) {
      c = static_cast<int>(clusters.size());
      clusters.emplace_back();
      areas.push_back(0);
    }
    Cluster& cl = clusters[static_cast<size_t>(c)];
    cl.pixels.push_back(i);
    const cv::Vec3d p = point(i);
    const double hh = height[static_cast<size_t>(i)];
    areas[static_cast<size_t>(c)] += p[2] * p[2] * px_area;
    cl.top = std::max(cl.top, hh);
    cl.bottom = std::min(cl.bottom, hh);
    const double lat = e1.dot(p), dep = e2.dot(p);
    cl.lat_min = std::min(cl.lat_min, lat);
    cl.lat_max = std::max(cl.lat_max, lat);
    cl.dep_min = std::min(cl.dep_min, dep);
    cl.dep_max = std::max(cl.dep_max, dep);
  }

  // Candidates reach person height and are tall themselves; the rest are fragments (an arm, a head
  // separated by a depth edge, a body cut by the image border or an occluder). Each fragment joins the
  // candidate whose footprint it touches; fragments left over that touch each other are joined and may
  // make a candidate together.
  const auto gap = [](const Cluster& a, const Cluster& b) {
    const double gl = std::max({0.0, a.lat_min - b.lat_max, b.lat_min - a.lat_max});
    const double gd = std::max({0.0, a.dep_min - b.dep_max, b.dep_min - a.dep_max});
    return std::hypot(gl, gd);
  };
  const auto is_candidate = [&](const Cluster& cl, double area) {
    return cl.top >= o.min_height_m && cl.top - cl.bottom >= 0.5 * o.min_height_m && area > 0.03;
  };
  for (size_t c = 0; c < clusters.size(); ++c) clusters[c].candidate = is_candidate(clusters[c], areas[c]);
  std::vector<int> cands;
  for (size_t c = 0; c < clusters.size(); ++c) {
    const Cluster& cl = clusters[c];
    if (cl.candidate && !cl.pixels.empty()) cands.push_back(static_cast<int>(c));
  }
  for (size_t c = 0; c < clusters.size(); ++c) {
    Cluster& cl = clusters[c];
    if (cl.candidate || areas[c] < 0.002 || cl.pixels.empty()) continue;
    int best = -1;
    double best_gap = o.merge_distance_m;
    for (int k : cands) {
      const double g = gap(clusters[static_cast<size_t>(k)], cl);
      if (g < best_gap) best_gap = g, best = k;
    }
    if (best < 0) continue;
    Cluster& p = clusters[static_cast<size_t>(best)];
    p.pixels.insert(p.pixels.end(), cl.pixels.begin(), cl.pixels.end());
    cl.pixels.clear();
    // The footprint stays the candidate's: fragments must not chain people together.
  }
  // Fragments left over (a body cut by the image border or an occluder) may make a person together.
  for (size_t a = 0; a < clusters.size(); ++a) {
    Cluster& ca = clusters[a];
    if (ca.candidate || areas[a] < 0.002 || ca.pixels.empty()) continue;
    for (size_t b = a + 1; b < clusters.size(); ++b) {
      Cluster& cb = clusters[b];
      if (cb.candidate || areas[b] < 0.002 || cb.pixels.empty() || gap(ca, cb) >= 0.5 * o.merge_distance_m) continue;
      ca.pixels.insert(ca.pixels.end(), cb.pixels.begin(), cb.pixels.end());
      cb.pixels.clear();
      ca.top = std::max(ca.top, cb.top), ca.bottom = std::min(ca.bottom, cb.bottom);
      ca.lat_min = std::min(ca.lat_min, cb.lat_min), ca.lat_max = std::max(ca.lat_max, cb.lat_max);
      ca.dep_min = std::min(ca.dep_min, cb.dep_min), ca.dep_max = std::max(ca.dep_max, cb.dep_max);
      areas[a] += areas[b];
      areas[b] = 0;
      b = a;  // the grown footprint may now touch earlier fragments
    }
    ca.candidate = is_candidate(ca, areas[a]) && areas[a] > 0.1;
    if (ca.candidate) cands.push_back(static_cast<int>(a));
  }

  // Heads: maxima of the lateral height profile within the person height range, at least a head
  // distance apart; every point joins the nearest head on the ground plane when close enough.
  struct Person {
    std::vector<int> pixels;
    double top = 0;
  };
  std::vector<Person> persons;
  const double bin = 0.05;
  for (int k : cands) {
    const Cluster& cl = clusters[static_cast<size_t>(k)];
    const int bins = std::max(1, static_cast<int>(std::ceil((cl.lat_max - cl.lat_min) / bin)) + 1);
    std::vector<double> prof(static_cast<size_t>(bins), -1e9), prof_dep(static_cast<size_t>(bins), 0);
    std::vector<int> prof_n(static_cast<size_t>(bins), 0);
    std::vector<cv::Vec3d> pts(cl.pixels.size());
    for (size_t j = 0; j < cl.pixels.size(); ++j) {
      const int i = cl.pixels[j];
      pts[j] = point(i);
      const double lat = e1.dot(pts[j]);
      const int b = std::clamp(static_cast<int>((lat - cl.lat_min) / bin), 0, bins - 1);
      prof[static_cast<size_t>(b)] = std::max(prof[static_cast<size_t>(b)], static_cast<double>(height[static_cast<size_t>(i)]));
    }
    // Depth of each bin's top: points within 0.2 m of the bin's top (the head).
    for (size_t j = 0; j < cl.pixels.size(); ++j) {
      const double lat = e1.dot(pts[j]);
      const int b = std::clamp(static_cast<int>((lat - cl.lat_min) / bin), 0, bins - 1);
      if (height[static_cast<size_t>(cl.pixels[j])] > prof[static_cast<size_t>(b)] - 0.2) {
        prof_dep[static_cast<size_t>(b)] += e2.dot(pts[j]);
        ++prof_n[static_cast<size_t>(b)];
      }
    }
    // A head is the highest bin within less than a head distance, in the person height range, and
    // stands out (topographic prominence >= 0.15 m) unless it is the cluster's top: shoulders do not.
    const int reach = std::max(1, static_cast<int>(std::round(o.head_distance_m / bin)) - 1);
    const auto usable = [&](int q) { return prof[static_cast<size_t>(q)] <= o.max_height_m; };
    double cluster_top = -1e9;
    for (int b = 0; b < bins; ++b)
      if (usable(b)) cluster_top = std::max(cluster_top, prof[static_cast<size_t>(b)]);
    std::vector<std::pair<double, double>> heads;  // lateral, depth
    for (int b = 0; b < bins; ++b) {
      const double p = prof[static_cast<size_t>(b)];
      if (p < o.min_height_m || p > o.max_height_m) continue;
      bool is_max = true;
      for (int q = std::max(0, b - reach); q <= std::min(bins - 1, b + reach) && is_max; ++q) {
        const double pq = prof[static_cast<size_t>(q)];
        if (q == b || !usable(q)) continue;
        if (pq > p || (pq == p && q < b)) is_max = false;
      }
      if (!is_max) continue;
      if (p < cluster_top) {
        double col = -1e9;  // the higher of the two lowest points on the way to higher ground
        for (int dir : {-1, 1}) {
          double lowest = p;
          bool higher = false;
          for (int q = b + dir; q >= 0 && q < bins; q += dir) {
            const double pq = prof[static_cast<size_t>(q)];
            if (usable(q) && pq > p) {
              higher = true;
              break;
            }
            lowest = std::min(lowest, pq < -1e8 ? p - 1.0 : pq);  // empty bins are gaps
          }
          if (higher) col = std::max(col, lowest);
        }
        if (col > -1e8 && p - col < 0.15) continue;
      }
      // The head's centre: the middle of the run of bins within 5 cm of its top (a flat head top
      // spans several bins; the first of them would pull the split towards one side).
      int lo = b, hi = b;
      while (lo - 1 >= std::max(0, b - reach) && prof[static_cast<size_t>(lo - 1)] >= p - 0.05 && usable(lo - 1)) --lo;
      while (hi + 1 <= std::min(bins - 1, b + reach) && prof[static_cast<size_t>(hi + 1)] >= p - 0.05 && usable(hi + 1)) ++hi;
      heads.emplace_back(cl.lat_min + (0.5 * (lo + hi) + 0.5) * bin,
                         prof_dep[static_cast<size_t>(b)] / prof_n[static_cast<size_t>(b)]);
    }
    if (heads.empty()) continue;
    const size_t first = persons.size();
    persons.resize(first + heads.size());
    for (size_t j = 0; j < cl.pixels.size(); ++j) {
      const double lat = e1.dot(pts[j]), dep = e2.dot(pts[j]);
      if (height[static_cast<size_t>(cl.pixels[j])] > o.max_height_m + 0.1) continue;
      size_t best = heads.size();
      double best_d = 1e9;
      for (size_t hd = 0; hd < heads.size(); ++hd) {
        const double dl = std::abs(lat - heads[hd].first), dd = std::abs(dep - heads[hd].second);
        if (dl > 0.5 * o.max_person_width_m || dd > 0.6) continue;
        if (dl < best_d) best_d = dl, best = hd;
      }
      if (best == heads.size()) continue;
      Person& ps = persons[first + best];
      ps.pixels.push_back(cl.pixels[j]);
      ps.top = std::max(ps.top, static_cast<double>(height[static_cast<size_t>(cl.pixels[j])]));
    }
  }

  // Keep people of plausible size, the largest first, then label them left to right.
  std::vector<std::pair<double, size_t>> kept;  // area, person
  for (size_t p = 0; p < persons.size(); ++p) {
    double area = 0, lmin = 1e9, lmax = -1e9;
    for (int i : persons[p].pixels) {
      const cv::Vec3d q = point(i);
      area += q[2] * q[2] * px_area;
      const double lat = e1.dot(q);
      lmin = std::min(lmin, lat);
      lmax = std::max(lmax, lat);
    }
    if (area < 0.08 || lmax - lmin < o.min_person_width_m || persons[p].top > o.max_height_m) continue;
    kept.emplace_back(area, p);
  }
  std::sort(kept.begin(), kept.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  if (static_cast<int>(kept.size()) > o.max_people) kept.resize(static_cast<size_t>(o.max_people));
  for (const auto& [area, p] : kept) {
    SegmentedPerson sp;
    int u0 = w, v0 = h, u1 = -1, v1 = -1;
    cv::Vec3d sum(0, 0, 0);
    for (int i : persons[p].pixels) {
      u0 = std::min(u0, i % w), u1 = std::max(u1, i % w);
      v0 = std::min(v0, i / w), v1 = std::max(v1, i / w);
      sum += point(i);
    }
    sp.box = cv::Rect(u0, v0, u1 - u0 + 1, v1 - v0 + 1);
    sp.pixels = static_cast<int>(persons[p].pixels.size());
    sp.height_m = persons[p].top;
    sp.centroid = sum / static_cast<double>(sp.pixels);
    sp.label = static_cast<int>(p);  // temporary: index into persons
    out.people.push_back(sp);
  }
  std::sort(out.people.begin(), out.people.end(), [](const auto& a, const auto& b) { return a.box.x < b.box.x; });
  for (size_t l = 0; l < out.people.size(); ++l) {
    for (int i : persons[static_cast<size_t>(out.people[l].label)].pixels)
      out.labels.at<uint8_t>(i / w, i % w) = static_cast<uint8_t>(l);
    out.people[l].label = static_cast<int>(l);
  }
  return out;
}

bool learn_recording_background(const RecordingReader& reader, DepthSegmenter& segmenter, int samples,
                                int min_frames) {
  const int n = reader.frame_count();
  if (n < min_frames || !reader.meta().streams.depth || samples < 1) return false;
  const int take = std::min(samples, n);
  int learnt = 0;
  for (int s = 0; s < take; ++s) {
    // A frame that cannot be read is left out here: the pass over the frames stops at it with its
    // error, after writing out the frames before it.
    try {
      const RgbdFrame f = reader.read_frame(static_cast<int>(static_cast<long>(s) * n / take));
      segmenter.learn_background(f.depth);
      ++learnt;
    } catch (const InputError&) {
    }
  }
  return learnt > 0;
}

nlohmann::json segmentation_to_json(int frame, const Segmentation& s) {
  nlohmann::json people = nlohmann::json::array();
  for (const auto& p : s.people)
    people.push_back({{"label", p.label},
                      {"box", {p.box.x, p.box.y, p.box.width, p.box.height}},
                      {"pixels", p.pixels},
                      {"height_m", std::round(p.height_m * 1000) / 1000},
                      {"centroid", {std::round(p.centroid[0] * 1000) / 1000, std::round(p.centroid[1] * 1000) / 1000,
                                    std::round(p.centroid[2] * 1000) / 1000}}});
  nlohmann::json j = {{"frame", frame}, {"people", people}, {"ground", nullptr}};
  if (s.ground) j["ground"] = {(*s.ground)[0], (*s.ground)[1], (*s.ground)[2], (*s.ground)[3]};
  return j;
}

MaskMatch match_masks(const cv::Mat& truth, const cv::Mat& predicted, int min_true_pixels) {
  CV_Assert(truth.type() == CV_8U && predicted.type() == CV_8U && truth.size() == predicted.size());
  constexpr int kN = kMaxBodies;
  long inter[kN][kN] = {}, tcount[kN] = {}, pcount[kN] = {};
  for (int v = 0; v < truth.rows; ++v) {
    const uint8_t* t = truth.ptr<uint8_t>(v);
    const uint8_t* p = predicted.ptr<uint8_t>(v);
    for (int u = 0; u < truth.cols; ++u) {
      const bool tv = t[u] < kN, pv = p[u] < kN;
      if (tv) ++tcount[t[u]];
      if (pv) ++pcount[p[u]];
      if (tv && pv) ++inter[t[u]][p[u]];
    }
  }
  std::vector<int> ts, ps;
  for (int i = 0; i < kN; ++i) {
    if (tcount[i] > 0 && tcount[i] >= min_true_pixels) ts.push_back(i);
    if (pcount[i] > 0) ps.push_back(i);
  }
  const auto iou = [&](int t, int p) {
    const long i = inter[t][p];
    return i ? static_cast<double>(i) / static_cast<double>(tcount[t] + pcount[p] - i) : 0.0;
  };
  // Exhaustive assignment (at most 6 true x 6 predicted): the maximal sum of IoU.
  std::vector<int> assign(ts.size(), -1), best_assign = assign;
  std::vector<bool> used(ps.size(), false);
  double best = -1;
  std::function<void(size_t, double)> search = [&](size_t ti, double sum) {
    if (ti == ts.size()) {
      if (sum > best) best = sum, best_assign = assign;
      return;
    }
    assign[ti] = -1;
    search(ti + 1, sum);
    for (size_t pj = 0; pj < ps.size(); ++pj) {
      if (used[pj]) continue;
      const double s = iou(ts[ti], ps[pj]);
      if (s <= 0) continue;
      used[pj] = true;
      assign[ti] = static_cast<int>(pj);
      search(ti + 1, sum + s);
      used[pj] = false;
      assign[ti] = -1;
    }
  };
  search(0, 0);
  MaskMatch m;
  int matched = 0;
  for (size_t ti = 0; ti < ts.size(); ++ti) {
    const int pj = best_assign[ti];
    m.iou.push_back(pj < 0 ? 0.0 : iou(ts[ti], ps[static_cast<size_t>(pj)]));
    matched += pj >= 0;
  }
  m.unmatched_predicted = static_cast<int>(ps.size()) - matched;
  return m;
}

}  // namespace bodyrec
