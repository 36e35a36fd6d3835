// Live RGB-D sensors through OpenNI2 (Kinect v1, Asus Xtion, Orbbec-class devices): colour and depth
// frames streamed into RgbdFrame, described by a RecordingMeta like a recording. Built when CMake finds
// Debian's libopenni2-dev (option BODYREC_WITH_OPENNI2); otherwise opening any device fails with an
// InputError that says so.
//
// The depth stream is registered to colour when the device supports it (then both cameras share the
// colour intrinsics and an identity transform); intrinsics come from the streams' fields of view.
#pragma once

#include <memory>
#include <string>

#include "bodyrec/rgbd/recording.h"

namespace bodyrec {

// True when this build has OpenNI2 support.
bool openni2_supported();

class OpenNiSource {
 public:
  // Opens `uri` ("" = the first device). InputError with a one-line message when OpenNI2 is missing,
  // cannot initialise, or no (such) device is connected.
  explicit OpenNiSource(const std::string& uri = "");
  ~OpenNiSource();
  OpenNiSource(const OpenNiSource&) = delete;
  OpenNiSource& operator=(const OpenNiSource&) = delete;

  const RecordingMeta& meta() const;
  // Next frame (depth CV_16U in mm, colour BGR when the device has colour). ProcessingError when the
  // device sends nothing for 2 seconds.
  void read(RgbdFrame& frame);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace bodyrec
