#include "bodyrec/reid/reid_split.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <random>
#include <regex>
#include <set>

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace {

std::regex compile(const std::string& pattern, const char* option) {
  std::regex re;
  try {
    re = std::regex(pattern, std::regex::ECMAScript);
  } catch (const std::regex_error& e) {
    throw UsageError(std::string(option) + " '" + pattern + "': not a valid regular expression (" + e.what() + ")");
  }
  if (re.mark_count() < 1) throw UsageError(std::string(option) + " '" + pattern + "' has no capture group ( )");
  return re;
}

bool is_image(const std::filesystem::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  static const std::set<std::string> kExt = {".png", ".jpg", ".jpeg", ".bmp", ".ppm", ".pgm", ".tif", ".tiff"};
  return kExt.count(ext) > 0;
}

}  // namespace

ReidDataset scan_reid_dataset(const std::string& root, const std::string& id_regex, const std::string& cam_regex) {
  const std::regex id_re = compile(id_regex, "--id-regex");
  const std::regex cam_re = compile(cam_regex, "--cam-regex");
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_directory(root, ec)) throw InputError(root + ": not a folder");
  struct Found {
    std::string path, id, cam;
  };
  std::vector<Found> found;
  ReidDataset data;
  data.root = root;
  for (fs::recursive_directory_iterator it(root, ec), end; !ec && it != end; it.increment(ec)) {
    if (!it->is_regular_file() || !is_image(it->path())) continue;
    const std::string rel = fs::relative(it->path(), root).generic_string();
    std::smatch id_m, cam_m;
    if (!std::regex_search(rel, id_m, id_re) || !std::regex_search(rel, cam_m, cam_re) || !id_m[1].matched ||
        !cam_m[1].matched) {
      ++data.skipped;
      continue;
    }
    found.push_back({rel, id_m[1].str(), cam_m[1].str()});
  }
  if (ec) throw InputError(root + ": cannot list the folder (" + ec.message() + ")");
  if (found.empty())
    throw InputError(root + ": no image path matches both --id-regex '" + id_regex + "' and --cam-regex '" +
                     cam_regex + "'");
  std::sort(found.begin(), found.end(), [](const Found& a, const Found& b) { return a.path < b.path; });
  std::set<std::string> ids, cams;
  for (const auto& f : found) ids.insert(f.id), cams.insert(f.cam);
  if (cams.size() != 2) {
    std::string list;
    for (const auto& c : cams) list += (list.empty() ? "" : ", ") + c;
    throw InputError(root + ": --cam-regex finds " + std::to_string(cams.size()) + " camera value(s) (" + list +
                     "); eval reid needs exactly two");
  }
  data.identities.assign(ids.begin(), ids.end());
  data.cameras[0] = *cams.begin();
  data.cameras[1] = *cams.rbegin();
  std::map<std::string, int> id_index;
  for (size_t i = 0; i < data.identities.size(); ++i) id_index[data.identities[i]] = static_cast<int>(i);
  std::vector<int> seen(data.identities.size(), 0);  // bit 0: first camera, bit 1: second camera
  for (const auto& f : found) {
    ReidImage image{f.path, id_index[f.id], f.cam == data.cameras[0] ? 0 : 1};
    seen[static_cast<size_t>(image.identity)] |= 1 << image.camera;
    data.images.push_back(image);
  }
  for (size_t i = 0; i < seen.size(); ++i)
    if (seen[i] == 3) data.in_both.push_back(static_cast<int>(i));
  if (data.in_both.empty())
    throw InputError(root + ": no identity has images in both cameras ('" + data.cameras[0] + "' and '" +
                     data.cameras[1] + "')");
  return data;
}

ReidSplit make_reid_split(const ReidDataset& data, int train_ids, uint32_t seed, int index) {
  const int available = static_cast<int>(data.in_both.size());
  if (train_ids < 0 || train_ids >= available)
    throw UsageError("--train-ids " + std::to_string(train_ids) + " leaves no identity to test (" +
                     std::to_string(available) + " identities are in both cameras)");
  // Fisher-Yates with a fixed generator so a seed gives the same split everywhere.
  std::mt19937 rng(seed * 1000003u + static_cast<uint32_t>(index));
  std::vector<int> ids = data.in_both;
  for (int i = available - 1; i > 0; --i) std::swap(ids[static_cast<size_t>(i)], ids[rng() % static_cast<uint32_t>(i + 1)]);
  std::vector<char> training(data.identities.size(), 0), testing(data.identities.size(), 0);
  for (int i = 0; i < available; ++i) (i < train_ids ? training : testing)[static_cast<size_t>(ids[i])] = 1;
  ReidSplit split;
  for (size_t i = 0; i < data.images.size(); ++i) {
    const ReidImage& image = data.images[i];
    const int idx = static_cast<int>(i);
    if (training[static_cast<size_t>(image.identity)]) split.train.push_back(idx);
    else if (image.camera == 1) split.gallery.push_back(idx);
    else if (testing[static_cast<size_t>(image.identity)]) split.probes.push_back(idx);
  }
  return split;
}

}  // namespace bodyrec
