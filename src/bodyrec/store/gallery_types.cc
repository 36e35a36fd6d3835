#include "bodyrec/store/gallery_types.h"

#include <array>
#include <cctype>
#include <ctime>

#include "bodyrec/core/parse_number.h"
#include "bodyrec/store/gallery.h"

namespace bodyrec {

namespace {
constexpr std::array<const char*, 7> kEventNames = {"enrolled", "recognised", "view_added", "scan_replaced",
                                                    "left",     "forgotten",  "pruned"};
}

const char* put_result_name(PutResult result) {
  switch (result) {
    case PutResult::kInserted: return "inserted";
    case PutResult::kReplaced: return "replaced";
    case PutResult::kKept: return "kept";
  }
  return "?";
}

const char* event_kind_name(EventKind kind) { return kEventNames.at(static_cast<size_t>(kind)); }

std::optional<EventKind> parse_event_kind(const std::string& name) {
  for (size_t i = 0; i < kEventNames.size(); ++i)
    if (name == kEventNames[i]) return static_cast<EventKind>(i);
  return std::nullopt;
}

int64_t to_unix_ms(GalleryTime time) {
  return std::chrono::duration_cast<std::chrono::milliseconds>(time.time_since_epoch()).count();
}

GalleryTime from_unix_ms(int64_t ms) {
  return GalleryTime(std::chrono::duration_cast<GalleryClock::duration>(std::chrono::milliseconds(ms)));
}

std::string format_utc(GalleryTime time) {
  const std::time_t t = GalleryClock::to_time_t(time);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buffer[32];
  std::strftime(buffer, sizeof(buffer), "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buffer;
}

std::optional<std::chrono::seconds> parse_duration(const std::string& text) {
  if (text.size() < 2) return std::nullopt;
  const auto number = parse_integer(std::string_view(text).substr(0, text.size() - 1));
  if (!number || *number < 0 || text[text.size() - 2] == ' ') return std::nullopt;
  long long unit = 0;
  switch (text.back()) {
    case 's': unit = 1; break;
    case 'm': unit = 60; break;
    case 'h': unit = 3600; break;
    case 'd': unit = 86400; break;
    case 'w': unit = 7 * 86400; break;
    default: return std::nullopt;
  }
  if (*number > (1LL << 40)) return std::nullopt;  // beyond any sensible retention; avoids overflow
  return std::chrono::seconds(*number * unit);
}

}  // namespace bodyrec
