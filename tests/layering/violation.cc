// Built with bodyrec_store's include path: a higher layer's header must not be reachable, so this file must
// not compile (tests/layering/check.cmake).
#include "bodyrec/reid/partial_scan.h"

int layering_violation() { return 0; }
