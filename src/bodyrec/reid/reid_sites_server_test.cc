// The several-sensors suite (reid_sites_suite_test.cc) on a private PostgreSQL server (ctest label `server`).
#include "bodyrec/reid/reid_sites_test_support.h"

namespace bodyrec::store::testing {

INSTANTIATE_TEST_SUITE_P(Db, ReidSites, ::testing::Values(sql::Dialect::kPostgres), backend_name);

}  // namespace bodyrec::store::testing
