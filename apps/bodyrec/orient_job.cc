#include "orient_job.h"

#include <chrono>
#include <cmath>
#include <array>
#include <map>
#include <optional>

#include "bodyrec/core/error.h"
#include "bodyrec/rgbd/ntu_skeleton.h"
#include "bodyrec/rgbd/segment.h"
#include "bodyrec/tracking/floor_tracker.h"
#include "bodyrec/tracking/slot_keys.h"

namespace bodyrec::cli {
namespace {

// The depth segmentation sometimes cuts one person in two (legs and trunk as separate clusters): two
// "people" standing within `within_m` of each other on the floor (camera X, Z of their centroids) are
// one body. Merges the smaller into the larger (labels, box, pixels, top, centroid).
void merge_fragments(Segmentation& seg, double within_m) {
  for (bool merged = true; merged;) {
    merged = false;
    for (size_t a = 0; a < seg.people.size() && !merged; ++a)
      for (size_t b = a + 1; b < seg.people.size() && !merged; ++b) {
        SegmentedPerson& pa = seg.people[a];
        SegmentedPerson& pb = seg.people[b];
        const double d = std::hypot(pa.centroid[0] - pb.centroid[0], pa.centroid[2] - pb.centroid[2]);
        if (d >= within_m) continue;
        SegmentedPerson& keep = pa.pixels >= pb.pixels ? pa : pb;
        const SegmentedPerson& gone = pa.pixels >= pb.pixels ? pb : pa;
        seg.labels.setTo(cv::Scalar(keep.label), seg.labels == gone.label);
        const double n = keep.pixels + gone.pixels;
        keep.centroid = (keep.centroid * keep.pixels + gone.centroid * gone.pixels) / n;
        keep.box |= gone.box;
        keep.pixels += gone.pixels;
        keep.height_m = std::max(keep.height_m, gone.height_m);
        seg.people.erase(seg.people.begin() + static_cast<long>(&gone == &pa ? a : b));
        merged = true;
      }
  }
}

// Where the bodies of a label image (body index or segmentation, labels 0..5) stand: per label, the
// median camera X and Z of its depth points (medians: edge pixels with the background's depth do not
// pull), whether it touches the image's first or last column, and its pixel counts.
std::array<LabelFloor, kMaxBodies> label_floors(const cv::Mat& labels, const cv::Mat& depth, const RecordingMeta& meta) {
  std::array<LabelFloor, kMaxBodies> out{};
  std::array<std::vector<float>, kMaxBodies> xs, zs;
  const bool has_depth = !depth.empty() && depth.size() == labels.size() && depth.type() == CV_16U;
  for (int v = 0; v < labels.rows; ++v) {
    const uint8_t* l = labels.ptr<uint8_t>(v);
    const uint16_t* dv = has_depth ? depth.ptr<uint16_t>(v) : nullptr;
    for (int u = 0; u < labels.cols; ++u) {
      if (l[u] >= kMaxBodies) continue;
      LabelFloor& b = out[l[u]];
      ++b.pixels;
      b.at_side |= u == 0 || u == labels.cols - 1;
      const uint16_t d = dv ? dv[u] : 0;
      if (!d) continue;
      const double z = d * meta.depth_unit_m;
      xs[l[u]].push_back(static_cast<float>((u - meta.depth.cx) / meta.depth.fx * z));
      zs[l[u]].push_back(static_cast<float>(z));
    }
  }
  const auto median = [](std::vector<float>& v) {
    std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
    return static_cast<double>(v[v.size() / 2]);
  };
  for (size_t i = 0; i < out.size(); ++i) {
    out[i].with_depth = static_cast<int>(zs[i].size());
    if (out[i].with_depth) out[i].floor = {median(xs[i]), median(zs[i])};
  }
  return out;
}

// The truth person whose body-index pixels overlap this label most (at least half of its pixels); without
// a body index, the one whose depth box overlaps the segment's box most (IoU >= 0.3).
int truth_by_overlap(const RgbdFrame& f, const cv::Mat& labels, int label, const cv::Rect& box) {
  if (!f.truth) return -1;
  if (f.body_index.empty()) {
    int best = -1;
    double best_iou = 0.3;
    for (size_t i = 0; i < f.truth->people.size(); ++i) {
      const cv::Rect& t = f.truth->people[i].depth_box;
      const double inter = (t & box).area(), uni = t.area() + box.area() - inter;
      if (uni > 0 && inter / uni >= best_iou) best = static_cast<int>(i), best_iou = inter / uni;
    }
    return best;
  }
  std::map<int, int> counts;
  int total = 0;
  for (int v = 0; v < labels.rows; ++v)
    for (int u = 0; u < labels.cols; ++u)
      if (labels.at<uint8_t>(v, u) == label) {
        ++total;
        const int b = f.body_index.at<uint8_t>(v, u);
        if (b != kNoBody) ++counts[b];
      }
  int best = -1, best_n = 0;
  for (const auto& [slot, n] : counts)
    if (n > best_n) best = slot, best_n = n;
  if (best < 0 || 2 * best_n < total) return -1;
  for (size_t i = 0; i < f.truth->people.size(); ++i)
    if (f.truth->people[i].body_index == best) return static_cast<int>(i);
  return -1;
}

}  // namespace

void add_orient_options(CLI::App& sub, OrientCliOptions& options) {
  sub.add_option("--views", options.views,
                 "robust (skeleton or depth axis, faces, motion, continuity) or thesis (Ch6 interval table)")
      ->check(CLI::IsMember({"robust", "thesis"}))
      ->capture_default_str();
  sub.add_flag("--no-faces", options.no_faces, "Do not run the face detector (thesis: the face flag is then unknown)");
  sub.add_flag("--depth-only", options.depth_only, "Ignore skeletons: orient from the body pixels' depth (robust only)");
  sub.add_option("--bodies-from", options.bodies_from,
                 "auto: skeletons, else body index, else own depth segmentation; or force skeleton, body-index "
                 "(slots only) or depth (segment the depth image, ignore the sensor's bodies)")
      ->check(CLI::IsMember({"auto", "skeleton", "body-index", "depth"}))
      ->capture_default_str();
  sub.add_option("--max-frames", options.max_frames, "Stop after this many frames; -1 = all");
  add_segment_options(sub, options.seg);
}

bool uses_own_segmentation(const RecordingMeta& meta, const OrientCliOptions& options) {
  return options.bodies_from == "depth" ||
         (options.bodies_from == "auto" && meta.streams.depth && !meta.streams.body_index &&
          (!meta.streams.bodies || options.depth_only));
}

bool is_skeleton_file(const std::string& input) {
  return input.size() > 9 && input.compare(input.size() - 9, 9, ".skeleton") == 0;
}

int run_orientation(const std::string& input, const OrientCliOptions& options,
                    const std::function<void(const OrientFrame&)>& sink) {
  OrientationOptions eo;
  eo.method = parse_view_method(options.views);
  eo.use_faces = !options.no_faces;
  eo.use_skeleton = !options.depth_only;
  if (options.depth_only && eo.method == ViewMethod::kThesis)
    throw UsageError("--depth-only needs --views robust (the thesis rule reads joint quaternions)");

  // Source: a recording, or an NTU skeleton file held in memory.
  std::optional<RecordingReader> reader;
  std::vector<std::vector<Body>> ntu;
  RecordingMeta meta;
  int frames = 0;
  if (is_skeleton_file(input)) {
    const NtuSkeleton s = read_ntu_skeleton(input);
    double rms[2];
    meta.sensor = "Kinect v2 (NTU RGB+D skeleton)";
    meta.streams.bodies = true;
    fit_ntu_cameras(s, meta, rms);
    ntu = ntu_bodies(s, input);
    frames = static_cast<int>(ntu.size());
  } else {
    reader.emplace(input);
    meta = reader->meta();
    frames = reader->frame_count();
  }
  if (options.max_frames >= 0) frames = std::min(frames, options.max_frames);
  if (options.depth_only && !meta.streams.depth)
    throw InputError(input + ": --depth-only needs a depth stream");

  const std::string& from = options.bodies_from;
  const auto need = [&](bool has, const char* stream) {
    if (!has) throw InputError(input + ": --bodies-from " + from + " needs a " + stream + " stream");
  };
  if (from == "skeleton") need(meta.streams.bodies, "bodies");
  if (from == "body-index") need(meta.streams.body_index, "body index");
  if (from == "depth") need(reader && meta.streams.depth, "depth");
  const bool use_skeletons = from == "skeleton" || (from == "auto" && meta.streams.bodies);
  const bool use_index = from == "body-index" || (from == "auto" && !meta.streams.bodies && meta.streams.body_index);

  OrientationEstimator estimator(meta, eo);
  std::optional<DepthSegmenter> segmenter;
  if (reader && uses_own_segmentation(meta, options)) segmenter = make_segmenter(*reader, options.seg);
  SlotKeys slot_keys(1.0 / meta.fps);
  FloorTracker floor_tracker;  // depth-only keys
  cv::Mat labels;
  int done = 0;
  for (int i = 0; i < frames; ++i, ++done) {
    RgbdFrame f;
    if (reader) {
      if (!reader->read(f)) break;
    } else {
      f.index = i;
      f.time_s = i / meta.fps;
      f.bodies = std::move(ntu[static_cast<size_t>(i)]);
    }
    labels = f.body_index;
    OrientFrame out{f, labels, {}, 0};
    std::vector<BodyRef> refs;
    const bool skeletons = use_skeletons && !f.bodies.empty() && !options.depth_only;
    if (use_skeletons && (skeletons || (options.depth_only && !f.body_index.empty() && !f.bodies.empty()))) {
      for (const Body& b : f.bodies) {
        BodyRef r = BodyRef::of(b, f.body_index);
        if (!skeletons) r.body = nullptr;
        refs.push_back(r);
        OrientedBody ob;
        ob.key = b.tracking_id;
        ob.slot = b.index;
        ob.body = skeletons ? &b : nullptr;
        if (f.truth)
          for (size_t t = 0; t < f.truth->people.size(); ++t)
            if (f.truth->people[t].tracking_id == b.tracking_id) ob.truth = static_cast<int>(t);
        out.bodies.push_back(ob);
      }
    } else if (use_index && !f.body_index.empty()) {
      const std::array<LabelFloor, kMaxBodies> floor = label_floors(f.body_index, f.depth, meta);
      for (int s = 0; s < kMaxBodies; ++s) {
        const LabelFloor& now = floor[static_cast<size_t>(s)];
        if (now.pixels < 200) continue;
        refs.push_back({slot_keys.key(s, f.time_s, now), nullptr, f.body_index, s});
        OrientedBody ob;
        ob.key = refs.back().key;
        ob.slot = s;
        if (f.truth)
          for (size_t t = 0; t < f.truth->people.size(); ++t)
            if (f.truth->people[t].body_index == s) ob.truth = static_cast<int>(t);
        out.bodies.push_back(ob);
      }
    } else if (segmenter && !f.depth.empty()) {
      Segmentation seg = segmenter->segment(f.depth);
      merge_fragments(seg, 0.3);
      labels = seg.labels;
      const std::array<LabelFloor, kMaxBodies> floor = label_floors(seg.labels, f.depth, meta);
      std::vector<cv::Vec2d> where;
      std::vector<bool> at_side;
      for (const auto& p : seg.people) {
        where.push_back(floor[static_cast<size_t>(p.label)].floor);
        at_side.push_back(floor[static_cast<size_t>(p.label)].at_side);
      }
      const std::vector<int> ids = floor_tracker.update(f.index, where, at_side);
      for (size_t k = 0; k < seg.people.size(); ++k) {
        if (ids[k] < 0) continue;  // not followed for long enough yet (a flicker of the segmentation)
        const SegmentedPerson& p = seg.people[k];
        refs.push_back({static_cast<uint64_t>(2000000 + ids[k]), nullptr, seg.labels, p.label});
        OrientedBody ob;
        ob.key = refs.back().key;
        ob.slot = p.label;
        ob.truth = truth_by_overlap(f, seg.labels, p.label, p.box);
        out.bodies.push_back(ob);
      }
    }
    const auto t0 = std::chrono::steady_clock::now();
    for (size_t b = 0; b < refs.size(); ++b) {
      std::optional<bool> oracle;
      if (options.face_oracle && f.truth && out.bodies[b].truth >= 0)
        oracle = std::abs(f.truth->people[static_cast<size_t>(out.bodies[b].truth)].yaw_deg) < 90;
      out.bodies[b].view = estimator.estimate(f, refs[b], oracle);
      out.bodies[b].face = estimator.last_face();
    }
    out.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    sink(out);
  }
  return done;
}

}  // namespace bodyrec::cli
