#include "bodyrec/rgbd/ntu_skeleton.h"

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "bodyrec/core/error.h"
#include "bodyrec/core/parse_number.h"

namespace bodyrec {
namespace {

// Reads the file line by line, splitting on whitespace (so '\r' of CRLF files is just whitespace).
class Lines {
 public:
  Lines(std::istream& in, const std::string& file) : file_(file), in_(in) {}
  // The next line's tokens; expects exactly `n` of them.
  std::vector<std::string> next(size_t n, const char* what) {
    std::string line;
    if (!std::getline(in_, line))
      throw InputError(file_ + ": unexpected end of file after line " + std::to_string(line_) + ", expected " + what);
    ++line_;
    std::istringstream s(line);
    std::vector<std::string> tokens;
    for (std::string t; s >> t;) tokens.push_back(t);
    if (tokens.size() != n)
      fail(std::string(what) + ": " + std::to_string(tokens.size()) + " values, expected " + std::to_string(n));
    return tokens;
  }
  double number(const std::string& t, const char* what) {
    const auto d = parse_double(t);
    if (!d || !std::isfinite(*d)) fail(std::string(what) + ": not a number: \"" + t + "\"");
    return *d;
  }
  long long integer(const std::string& t, const char* what, long long lo, long long hi) {
    const auto parsed = parse_integer(t);
    if (!parsed) fail(std::string(what) + ": not an integer: \"" + t + "\"");
    const long long v = *parsed;
    if (v < lo || v > hi) fail(std::string(what) + ": " + t + " outside " + std::to_string(lo) + ".." + std::to_string(hi));
    return v;
  }
  uint64_t id(const std::string& t, const char* what) {
    size_t used = 0;
    unsigned long long v = 0;
    try {
      v = std::stoull(t, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != t.size() || t[0] == '-') fail(std::string(what) + ": not an id: \"" + t + "\"");
    return v;
  }
  void expect_end() {
    std::string line;
    while (std::getline(in_, line)) {
      ++line_;
      if (line.find_first_not_of(" \t\r") != std::string::npos) fail("unexpected data after the last frame");
    }
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(file_ + ": line " + std::to_string(line_) + ": " + what);
  }

 private:
  std::string file_;
  std::istream& in_;
  int line_ = 0;
};

// Least squares of y = a * x + b (+ c * z when `with_z`); false when degenerate.
bool fit_line(const std::vector<std::array<double, 4>>& rows, bool with_z, cv::Vec3d& coef, double& rms) {
  const int n = static_cast<int>(rows.size());
  const int k = with_z ? 3 : 2;
  if (n < 20) return false;
  cv::Mat a(n, k, CV_64F), b(n, 1, CV_64F), x;
  for (int i = 0; i < n; ++i) {
    a.at<double>(i, 0) = rows[i][0];
    a.at<double>(i, 1) = 1.0;
    if (with_z) a.at<double>(i, 2) = rows[i][2];
    b.at<double>(i) = rows[i][3];
  }
  if (!cv::solve(a, b, x, cv::DECOMP_SVD)) return false;
  rms = std::sqrt(cv::norm(a * x - b, cv::NORM_L2SQR) / n);
  coef = {x.at<double>(0), x.at<double>(1), with_z ? x.at<double>(2) : 0.0};
  return std::isfinite(coef[0]) && std::abs(coef[0]) > 1;
}

}  // namespace

NtuSkeleton read_ntu_skeleton(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file + ": cannot open");
  return read_ntu_skeleton(in, file);
}

NtuSkeleton read_ntu_skeleton(std::istream& in, const std::string& file) {
  Lines lines(in, file);
  NtuSkeleton s;
  const auto frames = lines.integer(lines.next(1, "frame count")[0], "frame count", 0, 10000000);
  for (long long f = 0; f < frames; ++f) {
    const auto bodies = lines.integer(lines.next(1, "body count")[0], "body count", 0, kMaxBodies);
    std::vector<NtuBody> list;
    for (long long b = 0; b < bodies; ++b) {
      NtuBody body;
      const auto info = lines.next(10, "body line (id clippedEdges handLeftConfidence handLeftState "
                                       "handRightConfidence handRightState isRestricted leanX leanY trackingState)");
      body.id = lines.id(info[0], "body id");
      lines.integer(lines.next(1, "joint count")[0], "joint count", kJointCount, kJointCount);
      for (auto& joint : body.joints) {
        const auto v = lines.next(12, "joint line (x y z depthX depthY colorX colorY qw qx qy qz trackingState)");
        double d[11];
        for (int i = 0; i < 11; ++i) d[i] = lines.number(v[static_cast<size_t>(i)], "joint value");
        joint.position = {d[0], d[1], d[2]};
        joint.depth_px = {d[3], d[4]};
        joint.color_px = {d[5], d[6]};
        joint.orientation = {d[7], d[8], d[9], d[10]};
        joint.tracking_state = static_cast<int>(lines.integer(v[11], "joint trackingState", 0, 2));
      }
      list.push_back(body);
    }
    s.frames.push_back(std::move(list));
  }
  lines.expect_end();
  return s;
}

void fit_ntu_cameras(const NtuSkeleton& s, RecordingMeta& meta, double rms_px[2]) {
  meta.depth = kinect2_depth_intrinsics();
  meta.color = kinect2_color_intrinsics();
  meta.depth_to_color = kinect2_depth_to_color();
  rms_px[0] = rms_px[1] = -1;
  // Rows: (X/Z, -, 1/Z, pixel) for u; (-Y/Z, -, 1/Z, pixel) for v.
  std::vector<std::array<double, 4>> du, dv, cu, cv_;
  for (const auto& frame : s.frames)
    for (const auto& body : frame)
      for (const auto& j : body.joints) {
        const double z = j.position[2];
        if (j.tracking_state != 2 || !(z > 0.3)) continue;
        du.push_back({j.position[0] / z, 0, 1 / z, j.depth_px.x});
        dv.push_back({-j.position[1] / z, 0, 1 / z, j.depth_px.y});
        cu.push_back({j.position[0] / z, 0, 1 / z, j.color_px.x});
        cv_.push_back({-j.position[1] / z, 0, 1 / z, j.color_px.y});
      }
  cv::Vec3d a, b, c, d;
  double r[4];
  if (fit_line(du, false, a, r[0]) && fit_line(dv, false, b, r[1])) {
    meta.depth.fx = a[0], meta.depth.cx = a[1], meta.depth.fy = b[0], meta.depth.cy = b[1];
    rms_px[0] = std::hypot(r[0], r[1]);
  }
  // Colour: u = cx + fx (X + tx) / Z = cx + fx X/Z + (fx tx) / Z.
  if (fit_line(cu, true, c, r[2]) && fit_line(cv_, true, d, r[3])) {
    meta.color.fx = c[0], meta.color.cx = c[1], meta.color.fy = d[0], meta.color.cy = d[1];
    meta.depth_to_color.translation = {c[2] / c[0], d[2] / d[0], 0.0};
    rms_px[1] = std::hypot(r[2], r[3]);
  }
}

int import_ntu(const std::string& file, const std::string& out_dir, double rms_px[2]) {
  const NtuSkeleton s = read_ntu_skeleton(file);
  RecordingMeta meta;
  meta.sensor = "Kinect v2 (NTU RGB+D skeleton)";
  meta.fps = 30;
  meta.streams.bodies = true;
  fit_ntu_cameras(s, meta, rms_px);
  RecordingWriter writer(out_dir, meta);
  for (auto& bodies : ntu_bodies(s, file)) {
    RgbdFrame frame;
    frame.bodies = std::move(bodies);
    writer.write(frame);
  }
  return writer.frame_count();
}

std::vector<std::vector<Body>> ntu_bodies(const NtuSkeleton& s, const std::string& file) {
  std::vector<std::vector<Body>> out(s.frames.size());
  std::map<uint64_t, int> slots;  // body id -> slot, in order of first appearance
  for (size_t f = 0; f < s.frames.size(); ++f) {
    std::vector<int> used;
    for (const auto& nb : s.frames[f]) {
      auto it = slots.find(nb.id);
      if (it == slots.end()) it = slots.emplace(nb.id, static_cast<int>(slots.size()) % kMaxBodies).first;
      Body body;
      body.tracking_id = nb.id;
      body.index = it->second;
      for (int u : used)
        if (u == body.index)
          throw InputError(file + ": frame " + std::to_string(f) + ": more than 6 distinct body ids");
      used.push_back(body.index);
      for (int j = 0; j < kJointCount; ++j) {
        const NtuJoint& nj = nb.joints[static_cast<size_t>(j)];
        BodyJoint& bj = body.joints[static_cast<size_t>(j)];
        bj.position = nj.position;
        bj.tracking_state = nj.tracking_state;
        if (nj.orientation.norm() > 1e-6) bj.orientation = nj.orientation;
      }
      out[f].push_back(body);
    }
  }
  return out;
}

}  // namespace bodyrec
