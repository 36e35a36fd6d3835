#include "bodyrec/report/gallery_users.h"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/store/gallery.h"

namespace bodyrec::report {
namespace {

double unix_seconds(GalleryTime time) { return static_cast<double>(to_unix_ms(time)) / 1000.0; }

// The stored scan as a BGR image whose background (mask 0) is the page's slot colour, so a
// background-removed person reads as a person and not as a black box.
cv::Mat decode_scan(const StoredScan& scan, const std::string& where) {
  cv::Mat image = cv::imdecode(scan.image_png, cv::IMREAD_COLOR);
  if (image.empty()) throw InputError(where + ": the stored image does not decode");
  if (scan.mask_png.empty()) return image;
  const cv::Mat mask = cv::imdecode(scan.mask_png, cv::IMREAD_GRAYSCALE);
  if (mask.size() != image.size()) return image;  // an unusable mask hides nothing
  cv::Mat shown(image.size(), image.type(), cv::Scalar(249, 245, 241));  // #f1f5f9
  image.copyTo(shown, mask);
  return shown;
}

ReportUserEvent to_report_event(const Event& e) {
  ReportUserEvent out;
  out.kind = event_kind_name(e.kind);
  out.time = unix_seconds(e.time);
  if (e.view) out.view = view_name(*e.view);
  out.score = e.score;
  out.track = e.track;
  out.source = e.source;
  return out;
}

}  // namespace

std::vector<ReportUser> read_gallery_users(const std::string& path, bool images) {
  GalleryOptions options;
  options.read_only = true;
  Gallery gallery(path, options);
  std::vector<ReportUser> out;
  for (const User& u : gallery.users()) {
    ReportUser r;
    r.id = static_cast<int>(u.id);
    r.label = u.label;
    r.first_seen = unix_seconds(u.first_seen);
    r.last_seen = unix_seconds(u.last_seen);
    r.scanned = u.views;
    if (images)
      for (const StoredScan& scan : gallery.user_scans(u.id)) {
        if (scan.image_png.empty()) continue;  // stored with --no-images: a placeholder
        r.views[static_cast<size_t>(scan.view)] =
            decode_scan(scan, path + ": user " + std::to_string(u.id) + " view " + view_name(scan.view));
      }
    for (const Event& e : gallery.events(u.id)) r.events.push_back(to_report_event(e));
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace bodyrec::report
