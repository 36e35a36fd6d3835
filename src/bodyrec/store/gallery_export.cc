#include "bodyrec/store/gallery_export.h"

#include <sys/stat.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/store/gallery_json.h"

namespace bodyrec {

namespace {

void write_file(const std::filesystem::path& path, const void* data, size_t size) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
  out.close();
  if (!out) throw ProcessingError(path.string() + ": cannot write");
  std::filesystem::permissions(path, std::filesystem::perms::owner_read | std::filesystem::perms::owner_write);
}

}  // namespace

ExportReport export_user(Gallery& gallery, UserId id, const std::string& dir) {
  const auto user = gallery.user(id);
  if (!user) throw InputError(gallery.path() + ": no user " + std::to_string(id));
  std::error_code ec;
  if (!std::filesystem::exists(dir)) {
    std::filesystem::create_directories(dir, ec);
    if (ec) throw ProcessingError(dir + ": cannot create directory: " + ec.message());
    ::chmod(dir.c_str(), 0700);
  } else if (!std::filesystem::is_directory(dir)) {
    throw UsageError(dir + ": exists and is not a directory");
  }
  ExportReport report;
  nlohmann::json j = {{"gallery", gallery.path()}, {"user", user_to_json(*user)}};
  nlohmann::json scans = nlohmann::json::array();
  for (const StoredScan& scan : gallery.user_scans(id)) {
    nlohmann::json s = scan_to_json(scan);
    s["features"] = features_to_json(scan.features);
    const std::string view = view_name(scan.view);
    if (!scan.image_png.empty()) {
      const std::string name = view + "-image.png";
      write_file(std::filesystem::path(dir) / name, scan.image_png.data(), scan.image_png.size());
      s["image_file"] = name;
      report.files.push_back(name);
      ++report.images;
    }
    if (!scan.mask_png.empty()) {
      const std::string name = view + "-mask.png";
      write_file(std::filesystem::path(dir) / name, scan.mask_png.data(), scan.mask_png.size());
      s["mask_file"] = name;
      report.files.push_back(name);
      ++report.masks;
    }
    scans.push_back(s);
    ++report.scans;
  }
  j["scans"] = scans;
  nlohmann::json events = nlohmann::json::array();
  for (const Event& e : gallery.events(id)) events.push_back(event_to_json(e));
  report.events = static_cast<int>(events.size());
  j["events"] = events;
  const std::string text = j.dump(2) + "\n";
  write_file(std::filesystem::path(dir) / "user.json", text.data(), text.size());
  report.files.push_back("user.json");
  return report;
}

}  // namespace bodyrec
