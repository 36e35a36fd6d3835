#include "bodyrec/reid/reid_event.h"

namespace bodyrec {

const char* reid_event_name(ReidEventKind kind) {
  switch (kind) {
    case ReidEventKind::kEnrolled: return "enrolled";
    case ReidEventKind::kRecognised: return "recognised";
    case ReidEventKind::kViewAdded: return "view_added";
    case ReidEventKind::kLeft: return "left";
  }
  return "?";
}

}  // namespace bodyrec
