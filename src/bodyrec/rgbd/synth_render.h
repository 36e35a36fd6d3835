// Internals of synth.h: ray casting people's primitives into a camera with a z-buffer.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "bodyrec/rgbd/camera.h"
#include "bodyrec/rgbd/synth_model.h"

namespace bodyrec::synth {

struct Target {
  Intrinsics k;
  cv::Vec3f offset{0, 0, 0};  // added to scene points to get this camera's coordinates
  cv::Mat z;                  // CV_32F, metres along the optical axis; initialised with the background
  cv::Mat color;              // CV_8UC3 or empty (depth camera)
  cv::Mat label;              // CV_8U person slot or 255, or empty
  int pad = 0;                // coverage: also test this many pixels beyond each border
};

// Draws one person into the target (z-tested). With `coverage` (a CV_8U mask of size
// (w + 2 pad) x (h + 2 pad), zeroed by the caller), marks every pixel the person covers ignoring other
// objects and the image border (for the visible fraction).
void draw_person(const Look& look, const PersonModel& model, int slot, Target& target, cv::Mat* coverage);

// The empty room seen by a camera: floor, walls, ceiling. Fills target.z, and target.color when the
// caller allocated it (CV_8UC3 of the intrinsics' size).
void draw_room(Target& target, double camera_height);

}  // namespace bodyrec::synth
