// Boxes and detections shared by every stage, and the geometry on them (IoU, non-maximum suppression).
#pragma once

#include <vector>

#include <opencv2/core/types.hpp>

namespace bodyrec {

// An axis-aligned box in image pixels: top-left corner, width, height.
using Box = cv::Rect2d;

// One detected person: a box tight to the body (the PETS/MOT convention) and a score where higher
// means more confident. Scores are comparable only within one detector configuration.
struct Detection {
  Box box;
  double score = 0.0;
};

// Intersection over union of two boxes; 0 when either has no area.
double iou(const Box& a, const Box& b);

// Greedy non-maximum suppression.
// ENSURES: returns the detections sorted by decreasing score such that no two kept boxes overlap with
//   IoU > iou_threshold, and no box is inside a higher-scoring kept box by more than
//   containment_threshold of its own area (pass 1.0 to disable that test).
std::vector<Detection> non_max_suppression(std::vector<Detection> detections, double iou_threshold,
                                           double containment_threshold = 1.0);

// Scales a box about the origin (used to map boxes between resized and original images).
Box scale_box(const Box& b, double factor);

// Rounds a box to 0.01 px and a score to 1e-6, the precision every sink writes, so that results re-read
// from a written file (JSONL, MOT) are the very numbers bodyrec scored. Dividing by an exact power of ten
// gives the double nearest the decimal, which is what a parser of the text gets back.
Box round_box_for_output(const Box& b);
double round_score_for_output(double score);

// Gap between two boxes in pixels: 0 when they touch or overlap, else the Euclidean distance between
// their closest points.
double box_gap(const Box& a, const Box& b);

// Clips a box to an image of the given size; may return an empty box.
Box clip_box(const Box& b, const cv::Size& size);

}  // namespace bodyrec
