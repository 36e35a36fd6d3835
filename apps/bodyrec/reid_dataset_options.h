// Options shared by `bodyrec eval reid` and `bodyrec train-reid`: where the images are and how identity
// and camera are read from each path.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace bodyrec::cli {

struct ReidDatasetOptions {
  std::string root;
  std::string id_regex;
  std::string cam_regex;
};

inline void add_reid_dataset_options(CLI::App& sub, ReidDatasetOptions& o) {
  sub.add_option("--root", o.root, "Folder of person images (searched recursively)")->required();
  sub.add_option("--id-regex", o.id_regex,
                 "Regex on each image path relative to --root; its first capture group is the identity")
      ->required();
  sub.add_option("--cam-regex", o.cam_regex,
                 "Regex on the same path; first capture group is the camera (exactly two values; the smaller "
                 "one is the probe camera)")
      ->required();
}

}  // namespace bodyrec::cli
