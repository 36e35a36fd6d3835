// The gallery's SQL schema and the steps that upgrade an older gallery to the current version: one
// list of steps for both databases (store/connection.h), column types written as placeholders that
// each dialect spells its own way.
#pragma once

#include <string>

#include "bodyrec/store/connection.h"

namespace bodyrec::store {

// Marks a bodyrec gallery ("brg1"): SQLite's PRAGMA application_id; the key of PostgreSQL's advisory
// lock around schema upgrades.
constexpr int kGalleryApplicationId = 0x62726731;

// The DDL that upgrades schema `from` to `from + 1` in `dialect` (0 = a new gallery). The caller runs it
// inside one transaction and then records the new version (gallery_backend.h).
// REQUIRES: 0 <= from < kGallerySchemaVersion.
std::string schema_step(sql::Dialect dialect, int from);

// Column-type placeholders -> the dialect's words: {id} (an id never reused: AUTOINCREMENT / identity),
// {key} (a row id), {int}, {real}, {blob}.
std::string ddl(sql::Dialect dialect, const std::string& text);

}  // namespace bodyrec::store
