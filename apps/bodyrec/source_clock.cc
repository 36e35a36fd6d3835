#include "source_clock.h"

#include <algorithm>
#include <chrono>
#include <filesystem>

namespace bodyrec::cli {

std::optional<GalleryTime> file_source_start(const std::string& file, double duration_s, GalleryTime now) {
  std::error_code ec;
  const auto modified = std::filesystem::last_write_time(file, ec);
  if (ec) return std::nullopt;
  // file_time_type's clock is not system_clock in C++17: carry the offset across through "now" on both.
  const auto end = std::chrono::time_point_cast<GalleryClock::duration>(
      modified - std::filesystem::file_time_type::clock::now() + GalleryClock::now());
  const auto duration =
      std::chrono::duration_cast<GalleryClock::duration>(std::chrono::duration<double>(std::max(0.0, duration_s)));
  return std::min(end, now) - duration;
}

}  // namespace bodyrec::cli
