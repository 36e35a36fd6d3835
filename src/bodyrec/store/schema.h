// The gallery's SQL schema and the steps that upgrade an older file to the current version.
#pragma once

namespace bodyrec::sql {
class Database;
}

namespace bodyrec::store {

// PRAGMA application_id of a bodyrec gallery ("brg1"): tells a gallery from other SQLite files.
constexpr int kGalleryApplicationId = 0x62726731;

// Upgrades the open database from schema `from` (0 = empty file) to kGallerySchemaVersion, one step per
// version, inside the caller's transaction. Each step ends by setting PRAGMA user_version.
// REQUIRES: from < kGallerySchemaVersion.
void upgrade_schema(sql::Database& db, int from);

}  // namespace bodyrec::store
