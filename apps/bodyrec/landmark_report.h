// Printing landmark scores the same way in `train-shape` and `eval landmarks`.
#pragma once

#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

#include "bodyrec/landmarks/landmark_metrics.h"

namespace bodyrec::cli {

inline void print_landmark_scores(const std::string& title, const LandmarkScores& s) {
  std::printf("%s: %d persons\n", title.c_str(), s.persons);
  std::printf("  mean error        %.2f px (median %.2f, p90 %.2f)\n", s.mean_px, s.median_px, s.p90_px);
  std::printf("  / box height      %.4f (median %.4f, p90 %.4f)\n", s.mean_rel_height, s.median_rel_height,
              s.p90_rel_height);
  std::printf("  / image width     %.4f (the thesis's measure)\n", s.mean_rel_width);
  std::printf("  point-to-contour  %.2f px, %.4f of box height\n", s.contour_px, s.contour_rel_height);
  std::printf("  shape fitting     %.3f ms per person\n", s.ms_per_person);
}

inline nlohmann::json landmark_scores_json(const LandmarkScores& s) {
  return {{"mean_px", s.mean_px},
          {"median_px", s.median_px},
          {"p90_px", s.p90_px},
          {"mean_rel_height", s.mean_rel_height},
          {"median_rel_height", s.median_rel_height},
          {"p90_rel_height", s.p90_rel_height},
          {"mean_rel_width", s.mean_rel_width},
          {"point_to_contour_px", s.contour_px},
          {"point_to_contour_rel_height", s.contour_rel_height},
          {"persons", s.persons},
          {"ms_per_person", s.ms_per_person}};
}

}  // namespace bodyrec::cli
