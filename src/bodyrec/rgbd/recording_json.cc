// JSON side of the recording format: meta.json, bodies/NNNNNN.json and truth/NNNNNN.json, with
// validation whose messages name the file and the field ("DIR/bodies/000003.json: bodies[1].joints[4]
// (ShoulderLeft).orientation: quaternion is zero").
#include <cmath>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/io/image_header.h"
#include "bodyrec/rgbd/recording.h"

namespace bodyrec {
namespace {

using nlohmann::json;

// Where in which file a value sits; builds messages and child paths.
struct At {
  const std::string& file;
  std::string field;
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(file + ": " + (field.empty() ? "" : field + ": ") + what);
  }
  At key(const std::string& k) const { return {file, field.empty() ? k : field + "." + k}; }
  At item(size_t i) const { return {file, field + "[" + std::to_string(i) + "]"}; }
};

const json& member(const json& obj, const char* key, const At& at) {
  if (!obj.is_object()) at.fail("expected an object");
  const auto it = obj.find(key);
  if (it == obj.end()) at.key(key).fail("missing");
  return *it;
}

double number(const json& v, const At& at) {
  if (!v.is_number()) at.fail("expected a number");
  const double d = v.get<double>();
  if (!std::isfinite(d)) at.fail("not finite");
  return d;
}

long long integer(const json& v, const At& at, long long lo, long long hi) {
  if (!v.is_number_integer()) at.fail("expected an integer");
  const long long i = v.get<long long>();
  if (i < lo || i > hi) at.fail(std::to_string(i) + " outside " + std::to_string(lo) + ".." + std::to_string(hi));
  return i;
}

uint64_t unsigned_id(const json& v, const At& at) {
  if (!v.is_number_unsigned() && !(v.is_number_integer() && v.get<long long>() >= 0))
    at.fail("expected a non-negative integer");
  return v.get<uint64_t>();
}

std::string text(const json& v, const At& at) {
  if (!v.is_string()) at.fail("expected a string");
  return v.get<std::string>();
}

std::vector<double> numbers(const json& v, size_t n, const At& at) {
  if (!v.is_array() || v.size() != n) at.fail("expected an array of " + std::to_string(n) + " numbers");
  std::vector<double> out;
  for (size_t i = 0; i < n; ++i) out.push_back(number(v[i], at.item(i)));
  return out;
}

const json& array(const json& v, const At& at) {
  if (!v.is_array()) at.fail("expected an array");
  return v;
}

Intrinsics intrinsics_from(const json& j, const At& at) {
  Intrinsics k;
  k.width = static_cast<int>(integer(member(j, "width", at), at.key("width"), 1, 100000));
  k.height = static_cast<int>(integer(member(j, "height", at), at.key("height"), 1, 100000));
  // Refused here, when the recording opens, rather than frame by frame after the outputs exist.
  if (const std::string problem = frame_pixels_problem(k.width, k.height); !problem.empty()) at.fail(problem);
  k.fx = number(member(j, "fx", at), at.key("fx"));
  k.fy = number(member(j, "fy", at), at.key("fy"));
  k.cx = number(member(j, "cx", at), at.key("cx"));
  k.cy = number(member(j, "cy", at), at.key("cy"));
  if (k.fx <= 0 || k.fy <= 0) at.fail("fx and fy must be positive");
  return k;
}

json to_json(const Intrinsics& k) {
  return {{"width", k.width}, {"height", k.height}, {"fx", k.fx}, {"fy", k.fy}, {"cx", k.cx}, {"cy", k.cy}};
}

json vec(const cv::Vec3d& v) { return json::array({v[0], v[1], v[2]}); }

cv::Vec3d vec3(const json& v, const At& at) {
  const auto n = numbers(v, 3, at);
  return {n[0], n[1], n[2]};
}

cv::Rect rect_from(const json& v, const At& at) {
  if (!v.is_array() || v.size() != 4) at.fail("expected [x, y, width, height]");
  cv::Rect r;
  r.x = static_cast<int>(integer(v[0], at.item(0), -100000, 100000));
  r.y = static_cast<int>(integer(v[1], at.item(1), -100000, 100000));
  r.width = static_cast<int>(integer(v[2], at.item(2), 0, 100000));
  r.height = static_cast<int>(integer(v[3], at.item(3), 0, 100000));
  return r;
}

cv::Vec3b bgr_from_rgb(const json& v, const At& at) {
  if (!v.is_array() || v.size() != 3) at.fail("expected [r, g, b]");
  return {static_cast<uint8_t>(integer(v[2], at.item(2), 0, 255)), static_cast<uint8_t>(integer(v[1], at.item(1), 0, 255)),
          static_cast<uint8_t>(integer(v[0], at.item(0), 0, 255))};
}

json rgb(const cv::Vec3b& bgr) { return json::array({bgr[2], bgr[1], bgr[0]}); }

}  // namespace

json read_json_file(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file + ": cannot open");
  std::stringstream s;
  s << in.rdbuf();
  return parse_json_text(s.str(), file);
}

json parse_json_text(const std::string& text, const std::string& file) {
  try {
    return json::parse(text);
  } catch (const json::parse_error& e) {
    throw InputError(file + ": not valid JSON (byte " + std::to_string(e.byte) + ")");
  } catch (const json::exception& e) {
    // nlohmann reports a number too large for a double ("1e400") as out_of_range, not parse_error.
    throw InputError(file + ": not valid JSON (" + (e.id == 406 ? std::string("number out of range") : e.what()) + ")");
  }
}

RecordingMeta meta_from_json(const json& j, const std::string& file) {
  const At at{file, ""};
  RecordingMeta m;
  if (!j.is_object()) at.fail("expected a JSON object");
  if (text(member(j, "format", at), at.key("format")) != "bodyrec-rgbd")
    at.key("format").fail("expected \"bodyrec-rgbd\"");
  m.version = static_cast<int>(integer(member(j, "version", at), at.key("version"), 0, 1 << 30));
  if (m.version != kRecordingFormatVersion)
    at.key("version").fail("unknown version " + std::to_string(m.version) + " (this bodyrec reads version " +
                           std::to_string(kRecordingFormatVersion) + ")");
  m.sensor = text(member(j, "sensor", at), at.key("sensor"));
  m.fps = number(member(j, "fps", at), at.key("fps"));
  if (m.fps <= 0) at.key("fps").fail("must be positive");
  m.depth_unit_m = number(member(j, "depth_unit_m", at), at.key("depth_unit_m"));
  if (m.depth_unit_m <= 0) at.key("depth_unit_m").fail("must be positive");
  m.frame_count = static_cast<int>(integer(member(j, "frames", at), at.key("frames"), 0, 100000000));
  m.color_format = text(member(j, "color_format", at), at.key("color_format"));
  if (m.color_format != "png" && m.color_format != "jpg") at.key("color_format").fail("expected \"png\" or \"jpg\"");
  m.depth = intrinsics_from(member(j, "depth_intrinsics", at), at.key("depth_intrinsics"));
  m.color = intrinsics_from(member(j, "color_intrinsics", at), at.key("color_intrinsics"));
  const At ext = at.key("depth_to_color");
  const json& e = member(j, "depth_to_color", at);
  const auto r = numbers(member(e, "rotation", ext), 9, ext.key("rotation"));
  m.depth_to_color.rotation = cv::Matx33d(r.data());
  const cv::Matx33d should_be_eye = m.depth_to_color.rotation.t() * m.depth_to_color.rotation;
  if (cv::norm(should_be_eye - cv::Matx33d::eye()) > 1e-3 || cv::determinant(m.depth_to_color.rotation) < 0)
    ext.key("rotation").fail("not a rotation matrix (row-major 3x3, orthonormal, determinant +1)");
  m.depth_to_color.translation = vec3(member(e, "translation", ext), ext.key("translation"));
  const At sat = at.key("streams");
  const json& streams = array(member(j, "streams", at), sat);
  for (size_t i = 0; i < streams.size(); ++i) {
    const std::string s = text(streams[i], sat.item(i));
    bool* flag = s == "color" ? &m.streams.color
                 : s == "depth" ? &m.streams.depth
                 : s == "bodyindex" ? &m.streams.body_index
                 : s == "bodies" ? &m.streams.bodies
                 : s == "truth" ? &m.streams.truth : nullptr;
    if (!flag) sat.item(i).fail("unknown stream \"" + s + "\" (color, depth, bodyindex, bodies, truth)");
    *flag = true;
  }
  if (m.streams.body_index && !m.streams.depth) sat.fail("\"bodyindex\" needs \"depth\"");
  return m;
}

json to_json(const RecordingMeta& m) {
  json streams = json::array();
  if (m.streams.color) streams.push_back("color");
  if (m.streams.depth) streams.push_back("depth");
  if (m.streams.body_index) streams.push_back("bodyindex");
  if (m.streams.bodies) streams.push_back("bodies");
  if (m.streams.truth) streams.push_back("truth");
  const auto& r = m.depth_to_color.rotation;
  return {{"format", "bodyrec-rgbd"},
          {"version", m.version},
          {"sensor", m.sensor},
          {"fps", m.fps},
          {"depth_unit_m", m.depth_unit_m},
          {"frames", m.frame_count},
          {"color_format", m.color_format},
          {"streams", streams},
          {"depth_intrinsics", to_json(m.depth)},
          {"color_intrinsics", to_json(m.color)},
          {"depth_to_color",
           {{"rotation", json::array({r(0, 0), r(0, 1), r(0, 2), r(1, 0), r(1, 1), r(1, 2), r(2, 0), r(2, 1), r(2, 2)})},
            {"translation", vec(m.depth_to_color.translation)}}}};
}

std::vector<Body> bodies_from_json(const json& j, const std::string& file) {
  const At root{file, ""};
  const At at = root.key("bodies");
  const json& list = array(member(j, "bodies", root), at);
  if (list.size() > static_cast<size_t>(kMaxBodies)) at.fail(std::to_string(list.size()) + " bodies, at most 6");
  std::vector<Body> bodies;
  for (size_t b = 0; b < list.size(); ++b) {
    const At bat = at.item(b);
    Body body;
    body.tracking_id = unsigned_id(member(list[b], "tracking_id", bat), bat.key("tracking_id"));
    body.index = static_cast<int>(integer(member(list[b], "index", bat), bat.key("index"), 0, kMaxBodies - 1));
    for (const auto& other : bodies)
      if (other.index == body.index) bat.key("index").fail("slot " + std::to_string(body.index) + " used twice");
    const At jat = bat.key("joints");
    const json& joints = array(member(list[b], "joints", bat), jat);
    if (joints.size() != kJointCount) jat.fail(std::to_string(joints.size()) + " joints, expected 25");
    for (size_t i = 0; i < joints.size(); ++i) {
      const std::string name = joint_names()[i];
      const At at_j{file, jat.field + "[" + std::to_string(i) + "] (" + name + ")"};
      const json& jj = joints[i];
      if (text(member(jj, "name", at_j), at_j.key("name")) != name)
        at_j.key("name").fail("expected \"" + name + "\" (Kinect v2 joint order)");
      BodyJoint& joint = body.joints[i];
      joint.position = vec3(member(jj, "position", at_j), at_j.key("position"));
      const json& q = member(jj, "orientation", at_j);
      if (!q.is_null()) {
        const auto v = numbers(q, 4, at_j.key("orientation"));
        const Quaternion quat{v[0], v[1], v[2], v[3]};
        if (quat.norm() < 1e-6) at_j.key("orientation").fail("quaternion is zero (write null for none)");
        joint.orientation = quat;
      }
      joint.tracking_state = static_cast<int>(integer(member(jj, "tracking_state", at_j), at_j.key("tracking_state"), 0, 2));
    }
    bodies.push_back(body);
  }
  return bodies;
}

json bodies_to_json(const std::vector<Body>& bodies) {
  json list = json::array();
  for (const auto& b : bodies) {
    json joints = json::array();
    for (int i = 0; i < kJointCount; ++i) {
      const BodyJoint& jt = b.joints[static_cast<size_t>(i)];
      json q = nullptr;
      if (jt.orientation) q = json::array({jt.orientation->w, jt.orientation->x, jt.orientation->y, jt.orientation->z});
      joints.push_back({{"name", joint_names()[static_cast<size_t>(i)]},
                        {"position", vec(jt.position)},
                        {"orientation", q},
                        {"tracking_state", jt.tracking_state}});
    }
    list.push_back({{"tracking_id", b.tracking_id}, {"index", b.index}, {"joints", joints}});
  }
  return {{"bodies", list}};
}

FrameTruth truth_from_json(const json& j, const std::string& file) {
  const At root{file, ""};
  const At at = root.key("people");
  const json& list = array(member(j, "people", root), at);
  FrameTruth truth;
  for (size_t i = 0; i < list.size(); ++i) {
    const At p = at.item(i);
    const json& o = list[i];
    PersonTruth t;
    t.identity = static_cast<int>(integer(member(o, "identity", p), p.key("identity"), 0, 1 << 30));
    t.tracking_id = unsigned_id(member(o, "tracking_id", p), p.key("tracking_id"));
    t.body_index = static_cast<int>(integer(member(o, "body_index", p), p.key("body_index"), -1, kMaxBodies - 1));
    t.yaw_deg = number(member(o, "yaw_deg", p), p.key("yaw_deg"));
    if (t.yaw_deg < -180 || t.yaw_deg > 180) p.key("yaw_deg").fail("outside -180..180");
    t.visible_fraction = number(member(o, "visible_fraction", p), p.key("visible_fraction"));
    if (t.visible_fraction < 0 || t.visible_fraction > 1) p.key("visible_fraction").fail("outside 0..1");
    t.visible_pixels = static_cast<int>(integer(member(o, "visible_pixels", p), p.key("visible_pixels"), 0, 1 << 30));
    t.depth_box = rect_from(member(o, "depth_box", p), p.key("depth_box"));
    t.position = vec3(member(o, "position", p), p.key("position"));
    t.height_m = number(member(o, "height_m", p), p.key("height_m"));
    t.top = text(member(o, "top", p), p.key("top"));
    t.bottom = text(member(o, "bottom", p), p.key("bottom"));
    t.top_bgr = bgr_from_rgb(member(o, "top_rgb", p), p.key("top_rgb"));
    t.bottom_bgr = bgr_from_rgb(member(o, "bottom_rgb", p), p.key("bottom_rgb"));
    const At aat = p.key("accessories");
    const json& acc = array(member(o, "accessories", p), aat);
    for (size_t a = 0; a < acc.size(); ++a) t.accessories.push_back(text(acc[a], aat.item(a)));
    for (const auto& other : truth.people)
      if (other.identity == t.identity) p.key("identity").fail("identity " + std::to_string(t.identity) + " twice");
    truth.people.push_back(t);
  }
  return truth;
}

json to_json(const FrameTruth& truth) {
  json list = json::array();
  for (const auto& t : truth.people) {
    list.push_back({{"identity", t.identity},
                    {"tracking_id", t.tracking_id},
                    {"body_index", t.body_index},
                    {"yaw_deg", t.yaw_deg},
                    {"visible_fraction", t.visible_fraction},
                    {"visible_pixels", t.visible_pixels},
                    {"depth_box", json::array({t.depth_box.x, t.depth_box.y, t.depth_box.width, t.depth_box.height})},
                    {"position", vec(t.position)},
                    {"height_m", t.height_m},
                    {"top", t.top},
                    {"bottom", t.bottom},
                    {"top_rgb", rgb(t.top_bgr)},
                    {"bottom_rgb", rgb(t.bottom_bgr)},
                    {"accessories", t.accessories}});
  }
  return {{"people", list}};
}

}  // namespace bodyrec
