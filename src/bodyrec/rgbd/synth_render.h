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
  cv::Mat label;              // CV_8U person label (draw_person's `label`) or 255, or empty
  int pad = 0;                // coverage: also test this many pixels beyond each border
};

// Draws one person into the target (z-tested), writing `label` where they are nearest. With `coverage` (a
// CV_8U mask of size (w + 2 pad) x (h + 2 pad), zeroed by the caller), marks every pixel the person covers
// ignoring other objects and the image border (for the visible fraction).
void draw_person(const Look& look, const PersonModel& model, int label, Target& target, cv::Mat* coverage);

// Whether any pixel of the camera's image might show the person (conservative: primitives' screen boxes,
// occlusion ignored); false means certainly none does.
bool may_cover_image(const PersonModel& model, const Intrinsics& k);

// The empty room seen by a camera: floor, walls, ceiling. Fills target.z, and target.color when the
// caller allocated it (CV_8UC3 of the intrinsics' size).
void draw_room(Target& target, double camera_height);

}  // namespace bodyrec::synth
