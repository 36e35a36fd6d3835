#include "orient_job.h"

#include <chrono>
#include <cmath>
#include <array>
#include <map>
#include <optional>

#include "bodyrec/core/error.h"
#include "bodyrec/rgbd/ntu_skeleton.h"
#include "bodyrec/rgbd/segment.h"

namespace bodyrec::cli {
namespace {

// Keys for depth-only segments: nearest previous centroid within 0.5 m, else a new key.
class SegmentKeys {
 public:
  uint64_t key(const cv::Vec3d& c, double t) {
    int best = -1;
    double best_d = 0.5;
    for (size_t i = 0; i < tracks_.size(); ++i) {
      const double d = cv::norm(tracks_[i].c - c);
      if (t - tracks_[i].t < 1.0 && tracks_[i].t < t && d < best_d) best = static_cast<int>(i), best_d = d;
    }
    if (best < 0) {
      tracks_.push_back({c, t, 2000000 + next_++});
      return tracks_.back().key;
    }
    tracks_[static_cast<size_t>(best)].c = c;
    tracks_[static_cast<size_t>(best)].t = t;
    return tracks_[static_cast<size_t>(best)].key;
  }

 private:
  struct Track {
    cv::Vec3d c;
    double t;
    uint64_t key;
  };
  std::vector<Track> tracks_;
  uint64_t next_ = 0;
};

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
  if (from == "depth" ||
      (from == "auto" && reader && meta.streams.depth && !meta.streams.body_index && (!meta.streams.bodies || options.depth_only)))
    segmenter = make_segmenter(*reader, options.seg);
  std::array<int, kMaxBodies> slot_seen{}, slot_appearance{};  // body-index keys: per slot, last frame + 1, count
  SegmentKeys keys;
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
      int counts[256] = {0};
      for (int v = 0; v < f.body_index.rows; ++v)
        for (int u = 0; u < f.body_index.cols; ++u) ++counts[f.body_index.at<uint8_t>(v, u)];
      for (int s = 0; s < kMaxBodies; ++s) {
        if (counts[s] < 200) continue;
        const size_t k = static_cast<size_t>(s);
        // A slot empty for more than a third of a second (not a brief occlusion or dropout) holds a new body.
        if (slot_seen[k] == 0 || i - slot_seen[k] > static_cast<int>(meta.fps / 3)) ++slot_appearance[k];
        slot_seen[k] = i + 1;
        refs.push_back({static_cast<uint64_t>(1000000 + 10 * slot_appearance[k] + s), nullptr, f.body_index, s});
        OrientedBody ob;
        ob.key = refs.back().key;
        ob.slot = s;
        if (f.truth)
          for (size_t t = 0; t < f.truth->people.size(); ++t)
            if (f.truth->people[t].body_index == s) ob.truth = static_cast<int>(t);
        out.bodies.push_back(ob);
      }
    } else if (segmenter && !f.depth.empty()) {
      const Segmentation seg = segmenter->segment(f.depth);
      labels = seg.labels;
      for (const auto& p : seg.people) {
        refs.push_back({keys.key(p.centroid, f.time_s), nullptr, seg.labels, p.label});
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
