// Directory side of the recording format: reading and writing the per-frame files.
#include "bodyrec/rgbd/recording.h"

#include <cstdio>
#include <initializer_list>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/io/image_file.h"

namespace fs = std::filesystem;

namespace bodyrec {
namespace {

const char* type_name(int type) {
  switch (type) {
    case CV_8UC1: return "8-bit 1-channel";
    case CV_8UC3: return "8-bit 3-channel";
    case CV_8UC4: return "8-bit 4-channel";
    case CV_16UC1: return "16-bit 1-channel";
    case CV_16UC3: return "16-bit 3-channel";
    default: return "other type";
  }
}

void check_image(const cv::Mat& image, int type, const Intrinsics& k, const std::string& where, const char* what) {
  if (image.type() != type)
    throw InputError(where + ": " + what + " is " + type_name(image.type()) + ", expected " + type_name(type));
  if (image.cols != k.width || image.rows != k.height)
    throw InputError(where + ": " + what + " is " + std::to_string(image.cols) + "x" + std::to_string(image.rows) +
                     ", intrinsics say " + std::to_string(k.width) + "x" + std::to_string(k.height));
}

std::string number_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// "(1, -2.5, 3)"
std::string numbers_text(std::initializer_list<double> values) {
  std::string out;
  for (const double v : values) out += (out.empty() ? "(" : ", ") + number_text(v);
  return out + ")";
}

void write_file(const std::string& file, const std::string& text) {
  const std::string tmp = file + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    if (!out) throw ProcessingError(file + ": cannot write");
  }
  std::error_code ec;
  fs::rename(tmp, file, ec);
  if (ec) throw ProcessingError(file + ": cannot write (" + ec.message() + ")");
}

void write_image(const std::string& file, const cv::Mat& image) {
  bool ok = false;
  try {
    ok = cv::imwrite(file, image);
  } catch (const cv::Exception&) {
    ok = false;
  }
  if (!ok) throw ProcessingError(file + ": cannot write image");
}

}  // namespace

void check_joint_positions(const std::vector<Body>& bodies, const Intrinsics& depth, const std::string& file) {
  for (size_t b = 0; b < bodies.size(); ++b)
    for (int j = 0; j < kJointCount; ++j) {
      const BodyJoint& joint = bodies[b].joints[static_cast<size_t>(j)];
      if (joint.tracking_state == 0) continue;  // not tracked: the sensor measured nothing there
      const cv::Vec3d& p = joint.position;
      const std::string at = file + ": bodies[" + std::to_string(b) + "].joints[" + std::to_string(j) + "] (" +
                             joint_names()[static_cast<size_t>(j)] + ").position: " +
                             (joint.tracking_state == 2 ? "tracked" : "inferred") + " joint at " +
                             numbers_text({p[0], p[1], p[2]}) + " m ";
      if (!(p[2] > 0)) throw InputError(at + "is at or behind the camera (Z must be > 0)");
      if (p[2] > kMaxJointDepthM)
        throw InputError(at + "is further than " + number_text(kMaxJointDepthM) + " m from the camera");
      const cv::Point2d px = *project(depth, p);
      if (!(px.x >= -depth.width && px.x < 2.0 * depth.width && px.y >= -depth.height && px.y < 2.0 * depth.height))
        throw InputError(at + "projects to pixel " + numbers_text({px.x, px.y}) + ", more than the image's own size " +
                         "outside the " + std::to_string(depth.width) + "x" + std::to_string(depth.height) +
                         " depth image");
    }
}

bool is_recording_directory(const std::string& path) {
  std::error_code ec;
  return fs::is_directory(path, ec) && fs::exists(fs::path(path) / "meta.json", ec);
}

void validate_frame(const RgbdFrame& f, const RecordingMeta& m, const std::string& where) {
  if (m.streams.color) check_image(f.color, CV_8UC3, m.color, where, "colour image");
  if (m.streams.depth) check_image(f.depth, CV_16UC1, m.depth, where, "depth image");
  if (m.streams.body_index) {
    check_image(f.body_index, CV_8UC1, m.depth, where, "body index image");
    // Values 6..254 are not bodies: Kinect uses 0..5 and 255 for none.
    cv::Mat bad = (f.body_index > kMaxBodies - 1) & (f.body_index != kNoBody);
    std::vector<cv::Point> where_bad;
    if (cv::countNonZero(bad)) {
      cv::findNonZero(bad, where_bad);
      const cv::Point p = where_bad.front();
      throw InputError(where + ": body index value " + std::to_string(f.body_index.at<uint8_t>(p)) + " at (" +
                       std::to_string(p.x) + ", " + std::to_string(p.y) + "); expected 0..5 or 255");
    }
  }
  // Bodies passed in memory get the same checks as bodies read from JSON.
  if (m.streams.bodies) {
    bodies_from_json(bodies_to_json(f.bodies), where + " bodies");
    check_joint_positions(f.bodies, m.depth, where + " bodies");
  }
  if (m.streams.truth && !f.truth) throw InputError(where + ": truth missing");
}

RecordingReader::RecordingReader(const std::string& dir) : dir_(dir) {
  if (!fs::is_directory(dir)) throw InputError(dir + ": not a recording directory");
  const std::string meta_file = (fs::path(dir) / "meta.json").string();
  if (!fs::exists(meta_file)) throw InputError(meta_file + ": missing (not a bodyrec recording)");
  meta_ = meta_from_json(read_json_file(meta_file), meta_file);
}

bool RecordingReader::read(RgbdFrame& frame) {
  if (next_ >= meta_.frame_count) return false;
  frame = read_frame(next_++);
  return true;
}

RgbdFrame RecordingReader::read_frame(int index) const {
  const fs::path d(dir_);
  const std::string stem = frame_stem(index);
  RgbdFrame f;
  f.index = index;
  f.time_s = index / meta_.fps;
  std::string first_image;
  if (meta_.streams.color) {
    first_image = (d / "color" / (stem + "." + meta_.color_format)).string();
    f.color = read_image_file(first_image, cv::IMREAD_COLOR);
    check_image(f.color, CV_8UC3, meta_.color, first_image, "colour image");
  }
  if (meta_.streams.depth) {
    const std::string file = (d / "depth" / (stem + ".png")).string();
    f.depth = read_image_file(file, cv::IMREAD_UNCHANGED);
    check_image(f.depth, CV_16UC1, meta_.depth, file, "depth image");
  }
  if (meta_.streams.body_index) {
    const std::string file = (d / "bodyindex" / (stem + ".png")).string();
    f.body_index = read_image_file(file, cv::IMREAD_UNCHANGED);
    RecordingStreams only;
    only.body_index = true;
    RecordingMeta m = meta_;
    m.streams = only;
    validate_frame(f, m, file);
  }
  if (meta_.streams.bodies) {
    const std::string file = (d / "bodies" / (stem + ".json")).string();
    f.bodies = bodies_from_json(read_json_file(file), file);
    check_joint_positions(f.bodies, meta_.depth, file);
  }
  if (meta_.streams.truth) {
    const std::string file = (d / "truth" / (stem + ".json")).string();
    f.truth = truth_from_json(read_json_file(file), file);
  }
  return f;
}

RecordingWriter::RecordingWriter(const std::string& dir, RecordingMeta meta) : dir_(dir), meta_(std::move(meta)) {
  meta_.frame_count = 0;
  meta_.version = kRecordingFormatVersion;
  meta_.depth.check("depth intrinsics");
  meta_.color.check("colour intrinsics");
  std::error_code ec;
  if (fs::exists(dir) && !(fs::is_directory(dir) && fs::is_empty(dir)))
    throw UsageError(dir + ": output exists and is not an empty directory");
  fs::create_directories(dir, ec);
  if (ec) throw ProcessingError(dir + ": cannot create (" + ec.message() + ")");
  const fs::path d(dir);
  const auto make = [&](bool on, const char* sub) {
    if (on) fs::create_directories(d / sub, ec);
    if (ec) throw ProcessingError((d / sub).string() + ": cannot create (" + ec.message() + ")");
  };
  make(meta_.streams.color, "color");
  make(meta_.streams.depth, "depth");
  make(meta_.streams.body_index, "bodyindex");
  make(meta_.streams.bodies, "bodies");
  make(meta_.streams.truth, "truth");
  write_meta();
}

void RecordingWriter::write(const RgbdFrame& f) {
  const std::string stem = frame_stem(meta_.frame_count);
  validate_frame(f, meta_, dir_ + " frame " + std::to_string(meta_.frame_count));
  const fs::path d(dir_);
  if (meta_.streams.color) write_image((d / "color" / (stem + "." + meta_.color_format)).string(), f.color);
  if (meta_.streams.depth) write_image((d / "depth" / (stem + ".png")).string(), f.depth);
  if (meta_.streams.body_index) write_image((d / "bodyindex" / (stem + ".png")).string(), f.body_index);
  if (meta_.streams.bodies) write_file((d / "bodies" / (stem + ".json")).string(), bodies_to_json(f.bodies).dump() + "\n");
  if (meta_.streams.truth) write_file((d / "truth" / (stem + ".json")).string(), to_json(*f.truth).dump() + "\n");
  ++meta_.frame_count;
  write_meta();
}

void RecordingWriter::write_meta() const {
  write_file((fs::path(dir_) / "meta.json").string(), to_json(meta_).dump(2) + "\n");
}

}  // namespace bodyrec
