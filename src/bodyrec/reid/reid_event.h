// What online re-identification reports as it decides: a body enrolled as a new user, recognised as a known
// one, a view added to a user's model, a user's body gone.
#pragma once

#include <cstdint>
#include <optional>

#include "bodyrec/core/view.h"
#include "bodyrec/store/gallery_types.h"

namespace bodyrec {

enum class ReidEventKind { kEnrolled, kRecognised, kViewAdded, kLeft };
const char* reid_event_name(ReidEventKind kind);  // "enrolled", "recognised", "view_added", "left"

struct ReidEvent {
  ReidEventKind kind = ReidEventKind::kRecognised;
  UserId user = 0;
  uint64_t track = 0;
  std::optional<View> view;     // the view matched / added / enrolled with
  std::optional<double> score;  // recognised: the winning mean similarity
};

}  // namespace bodyrec
