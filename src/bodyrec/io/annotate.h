// Drawing helpers for annotated output: labelled boxes, polylines, arrows and a caption line.
#pragma once

#include <string>

#include <opencv2/core.hpp>

#include "bodyrec/core/geometry.h"
#include "bodyrec/core/role.h"

namespace bodyrec {

// Colours (BGR) used across the annotated outputs; the thesis's role colours among them.
namespace colors {
const cv::Scalar kBlue(255, 0, 0), kGreen(0, 200, 0), kRed(0, 0, 255), kYellow(0, 255, 255),
    kWhite(255, 255, 255), kBlack(0, 0, 0), kOrange(0, 165, 255);
}

// The thesis's drawing colours (BGR): leader blue, member green, non-member red; potential member orange,
// unknown white. One definition for the annotated video and the HTML report.
cv::Scalar role_color(Role role);

// A stable, well-spread colour per track id (golden-angle hue steps), for drawing people by identity.
cv::Scalar id_color(int id);

// A rectangle with an optional label drawn on a filled tag above it.
void draw_labelled_box(cv::Mat& image, const Box& box, const cv::Scalar& color, const std::string& label,
                       int thickness = 2);

// A caption in the top-left corner on a dark band (frame number, stage info).
void draw_caption(cv::Mat& image, const std::string& text);

}  // namespace bodyrec
