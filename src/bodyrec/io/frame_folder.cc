#include "bodyrec/io/frame_folder.h"

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "bodyrec/core/error.h"

namespace fs = std::filesystem;

namespace bodyrec {

bool is_frame_file_name(const std::string& name) {
  if (name.size() < 10 || name.compare(name.size() - 4, 4, ".png") != 0) return false;
  for (size_t i = 0; i < 6; ++i)
    if (!std::isdigit(static_cast<unsigned char>(name[i]))) return false;
  return true;
}

FrameFolder::FrameFolder(std::string dir) : dir_(std::move(dir)) {
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec) throw ProcessingError("cannot create folder " + dir_ + ": " + ec.message());
  for (fs::directory_iterator it(dir_, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (is_frame_file_name(name) && it->is_regular_file(ec)) earlier_.insert(name);
  }
}

std::string frame_stem(int index) {
  char digits[16];
  std::snprintf(digits, sizeof digits, "%06d", index);
  return digits;
}

std::string FrameFolder::file(int frame, const std::string& tag) {
  const std::string name = frame_stem(frame) + tag + ".png";
  written_.insert(name);
  return (fs::path(dir_) / name).string();
}

size_t FrameFolder::stale() const {
  size_t n = 0;
  for (const std::string& name : earlier_) n += written_.count(name) == 0;
  return n;
}

std::string FrameFolder::stale_note() const {
  std::vector<const std::string*> left;
  for (const std::string& name : earlier_)
    if (written_.count(name) == 0) left.push_back(&name);
  if (left.empty()) return "";
  return dir_ + " holds " + std::to_string(left.size()) + " frame file" + (left.size() == 1 ? "" : "s") +
         " of an earlier run that this run did not replace (" + *left.front() +
         (left.size() > 1 ? " ... " + *left.back() : "") + ")";
}

}  // namespace bodyrec
