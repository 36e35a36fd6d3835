// The two-camera re-identification protocol of `bodyrec eval reid`: images found under a root folder,
// identity and camera read from each relative path by regular expressions, random train/test splits.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace bodyrec {

struct ReidImage {
  std::string path;  // relative to the root, '/' separated
  int identity = 0;  // index into ReidDataset::identities
  int camera = 0;    // 0 = first camera (probes), 1 = second camera (gallery)
};

struct ReidDataset {
  std::string root;
  std::vector<ReidImage> images;        // sorted by path
  std::vector<std::string> identities;  // first capture group of the identity regex, sorted
  std::string cameras[2];               // the two camera values, sorted: [0] is "first"
  std::vector<int> in_both;             // identities with images in both cameras, ascending
  int skipped = 0;                      // image files whose path matches neither regex
};

// Lists the image files (.png .jpg .jpeg .bmp .ppm .pgm .tif .tiff) under root, recursively.
// Throws UsageError when a regex does not compile or has no capture group; InputError when root is not
// a folder, no image matches both regexes, the cameras are not exactly two, or no identity is in both.
ReidDataset scan_reid_dataset(const std::string& root, const std::string& id_regex, const std::string& cam_regex);

struct ReidSplit {
  std::vector<int> train;    // image indices of the training identities (both cameras)
  std::vector<int> probes;   // first-camera images of the other identities present in both cameras
  std::vector<int> gallery;  // every second-camera image whose identity is not a training one
};

// Split number `index` for `seed`: train_ids identities drawn at random among those in both cameras.
// Throws UsageError when train_ids leaves no identity to test (train_ids >= in_both.size()).
ReidSplit make_reid_split(const ReidDataset& data, int train_ids, uint32_t seed, int index);

}  // namespace bodyrec
