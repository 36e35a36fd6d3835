#include "bodyrec/reid/rgbd_bodies.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "bodyrec/core/error.h"

namespace bodyrec {
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

template <typename Same>
int truth_where(const RgbdFrame& f, Same same) {
  if (!f.truth) return -1;
  for (size_t t = 0; t < f.truth->people.size(); ++t)
    if (same(f.truth->people[t])) return static_cast<int>(t);
  return -1;
}

}  // namespace

const char* to_string(BodySource source) {
  switch (source) {
    case BodySource::kAuto: return "auto";
    case BodySource::kSkeleton: return "skeleton";
    case BodySource::kBodyIndex: return "body-index";
    case BodySource::kDepth: return "depth";
  }
  return "?";
}

std::optional<BodySource> parse_body_source(const std::string& text) {
  for (BodySource s : {BodySource::kAuto, BodySource::kSkeleton, BodySource::kBodyIndex, BodySource::kDepth})
    if (text == to_string(s)) return s;
  return std::nullopt;
}

bool uses_own_segmentation(const RecordingMeta& meta, const RgbdBodiesOptions& options) {
  return options.from == BodySource::kDepth ||
         (options.from == BodySource::kAuto && meta.streams.depth && !meta.streams.body_index &&
          (!meta.streams.bodies || options.depth_only));
}

RgbdBodyFinder::RgbdBodyFinder(const RecordingMeta& meta, const RgbdBodiesOptions& options,
                               std::optional<DepthSegmenter> segmenter, const std::string& name)
    : meta_(meta), options_(options), segmenter_(std::move(segmenter)), slot_keys_(1.0 / meta.fps) {
  const auto need = [&](bool has, const char* stream) {
    if (!has)
      throw InputError(name + ": taking bodies from " + to_string(options.from) + " needs a " + stream + " stream");
  };
  if (options.from == BodySource::kSkeleton) need(meta.streams.bodies, "bodies");
  if (options.from == BodySource::kBodyIndex) need(meta.streams.body_index, "body index");
  if (options.from == BodySource::kDepth) need(meta.streams.depth, "depth");
  if (options.depth_only && !meta.streams.depth) throw InputError(name + ": depth_only needs a depth stream");
  if (!segmenter_ && uses_own_segmentation(meta, options) && meta.streams.depth)
    throw UsageError("RgbdBodyFinder: bodies from depth need a DepthSegmenter");
  use_skeletons_ = options.from == BodySource::kSkeleton || (options.from == BodySource::kAuto && meta.streams.bodies);
  use_index_ = options.from == BodySource::kBodyIndex ||
               (options.from == BodySource::kAuto && !meta.streams.bodies && meta.streams.body_index);
  if (!uses_own_segmentation(meta, options)) segmenter_.reset();
}

FoundBodies RgbdBodyFinder::find(const RgbdFrame& f) {
  FoundBodies out;
  out.labels = f.body_index;
  const bool skeletons = use_skeletons_ && !f.bodies.empty() && !options_.depth_only;
  if (use_skeletons_ && (skeletons || (options_.depth_only && !f.body_index.empty() && !f.bodies.empty()))) {
    for (const Body& b : f.bodies) {
      FoundBody found{BodyRef::of(b, f.body_index), -1};
      if (!skeletons) found.ref.body = nullptr;
      found.truth = truth_where(f, [&](const PersonTruth& t) { return t.tracking_id == b.tracking_id; });
      out.bodies.push_back(found);
    }
  } else if (use_index_ && !f.body_index.empty()) {
    const std::array<LabelFloor, kMaxBodies> floor = label_floors(f.body_index, f.depth, meta_);
    for (int s = 0; s < kMaxBodies; ++s) {
      const LabelFloor& now = floor[static_cast<size_t>(s)];
      if (now.pixels < options_.min_slot_pixels) continue;
      FoundBody found{{slot_keys_.key(s, f.time_s, now), nullptr, f.body_index, s}, -1};
      found.truth = truth_where(f, [&](const PersonTruth& t) { return t.body_index == s; });
      out.bodies.push_back(found);
    }
  } else if (segmenter_ && !f.depth.empty()) {
    Segmentation seg = segmenter_->segment(f.depth);
    merge_fragments(seg, options_.merge_within_m);
    out.labels = seg.labels;
    const std::array<LabelFloor, kMaxBodies> floor = label_floors(seg.labels, f.depth, meta_);
    std::vector<cv::Vec2d> where;
    std::vector<bool> at_side;
    for (const auto& p : seg.people) {
      where.push_back(floor[static_cast<size_t>(p.label)].floor);
      at_side.push_back(floor[static_cast<size_t>(p.label)].at_side);
    }
    const std::vector<int> ids = floor_tracker_.update(f.index, where, at_side);
    for (size_t k = 0; k < seg.people.size(); ++k) {
      if (ids[k] < 0) continue;  // not followed for long enough yet (a flicker of the segmentation)
      const SegmentedPerson& p = seg.people[k];
      FoundBody found{{kFloorKeyBase + static_cast<uint64_t>(ids[k]), nullptr, seg.labels, p.label}, -1};
      found.truth = truth_by_overlap(f, seg.labels, p.label, p.box);
      out.bodies.push_back(found);
    }
  }
  return out;
}

}  // namespace bodyrec
