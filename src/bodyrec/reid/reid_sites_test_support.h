// The fixture of reid_sites_suite_test.cc, declared here so that each test program instantiates the suite
// for its database: SQLite in gallery_reid_store_test.cc, PostgreSQL in reid_sites_server_test.cc.
#pragma once

#include "bodyrec/store/gallery_backend_test_support.h"

namespace bodyrec::store::testing {

class ReidSites : public GalleryBackendTest {
 protected:
  // A new gallery with its schema; its location.
  std::string gallery() {
    const std::string path = fresh();
    Gallery g(path, creating());
    return path;
  }
};

}  // namespace bodyrec::store::testing
