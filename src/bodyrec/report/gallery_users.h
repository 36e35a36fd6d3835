// Gallery users for the report: the store's users, their 8 partial-scan views and their events, read
// from a gallery file without changing it.
#pragma once

#include <string>
#include <vector>

#include "bodyrec/report/run_data.h"

namespace bodyrec::report {

// Every user of the gallery at `path`, by id: label, first/last seen, one decoded image per stored view
// (reid/view.h kAllViews order; background outside the stored mask painted the page's slot colour) and
// the user's events, oldest first. With `images` false no pixel is decoded: only which views have a
// scan. Opens the file read-only (nothing written, no file created). Throws the store's InputError
// naming the file when it is missing, not an SQLite database, another application's database or from a
// newer schema; InputError naming the user and view when a stored image does not decode.
std::vector<ReportUser> read_gallery_users(const std::string& path, bool images = true);  // file or postgresql:// URI

}  // namespace bodyrec::report
