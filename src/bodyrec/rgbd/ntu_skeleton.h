// NTU RGB+D `.skeleton` files (Kinect v2 skeletons as text; CRLF or LF line ends): parsing, and turning
// them into a bodies-only recording.
#pragma once

#include <array>
#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include "bodyrec/rgbd/recording.h"

namespace bodyrec {

struct NtuJoint {
  cv::Vec3d position;     // camera space, metres
  cv::Point2d depth_px;   // projection into the 512x424 depth image
  cv::Point2d color_px;   // projection into the 1920x1080 colour image
  Quaternion orientation; // all zero for Kinect end joints
  int tracking_state = 0;
};

struct NtuBody {
  uint64_t id = 0;
  std::array<NtuJoint, kJointCount> joints;
};

struct NtuSkeleton {
  std::vector<std::vector<NtuBody>> frames;
};

// Parses a whole file. InputError naming the file, line and field on any deviation from the grammar
// (counts, 25 joints, 12 values per joint line, 10 per body line, numbers, end of file).
NtuSkeleton read_ntu_skeleton(const std::string& file);
// The same from a stream; `name` names the source in messages.
NtuSkeleton read_ntu_skeleton(std::istream& in, const std::string& name);

// Fits depth intrinsics (u = cx + fx X/Z, v = cy - fy Y/Z) and colour intrinsics plus a depth-to-colour
// translation from the joints' own projections; Kinect v2 defaults when fewer than 20 joints. `rms_px`
// receives the depth and colour fit residuals.
void fit_ntu_cameras(const NtuSkeleton& s, RecordingMeta& meta, double rms_px[2]);

// The skeleton's bodies per frame as recording bodies: slots in order of first appearance of a body id,
// zero quaternions as "no orientation". InputError naming `file` and the frame when a frame has more
// than 6 distinct ids.
std::vector<std::vector<Body>> ntu_bodies(const NtuSkeleton& s, const std::string& file);

// Writes the skeleton as a recording with the `bodies` stream only (no colour or depth exists). Bodies
// take body slots in order of first appearance. Zero quaternions become "no orientation".
// Returns the number of frames written.
int import_ntu(const std::string& file, const std::string& out_dir, double rms_px[2]);

}  // namespace bodyrec
