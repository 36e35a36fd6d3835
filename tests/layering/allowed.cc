// Built with bodyrec_store's include path: a lower layer's header is reachable.
#include "bodyrec/core/view.h"

int layering_allowed() { return bodyrec::kViewCount; }
