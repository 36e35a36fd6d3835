// Organised PCD point clouds with colour (PCL's .pcd, version 0.7 and older headers): FIELDS must
// include x y z and rgb or rgba; DATA ascii, binary or binary_compressed (LZF, field-major after
// decompression; decompressed with Debian's liblzf). Import turns one cloud into a one-frame recording.
#pragma once

#include <iosfwd>
#include <string>

#include "bodyrec/rgbd/recording.h"

namespace bodyrec {

struct PcdCloud {
  int width = 0, height = 0;  // organised: height > 1
  cv::Mat xyz;                // CV_32FC3, PCL camera frame (x right, y down, z forward), NaN = no point
  cv::Mat color;              // CV_8UC3, BGR
};

// Reads a PCD file. InputError naming the file and the header line or data field at fault (unknown
// DATA kind, missing x/y/z/rgb, sizes that disagree, truncated or corrupt data, unorganised cloud).
PcdCloud read_pcd(const std::string& file);
// The same from a (binary) stream; `name` names the source in messages.
PcdCloud read_pcd(std::istream& in, const std::string& name);

// Fits u = cx + fx x/z and v = cy + fy y/z over the valid points (an organised cloud keeps pixel order).
// InputError when fewer than 100 valid points.
Intrinsics fit_pcd_intrinsics(const PcdCloud& cloud, const std::string& file, double* rms_px = nullptr);

// Writes the cloud as a one-frame recording: colour and depth (z in millimetres, 0 where NaN) registered
// to each other (same intrinsics, identity extrinsics). Returns the fitted intrinsics.
Intrinsics import_pcd(const std::string& file, const std::string& out_dir, double* rms_px = nullptr);

}  // namespace bodyrec
