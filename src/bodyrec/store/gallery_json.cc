#include "bodyrec/store/gallery_json.h"

#include <nlohmann/json.hpp>

#include "bodyrec/store/gallery.h"

namespace bodyrec {

std::string describe_matrix(const cv::Mat& m) {
  static const char* const kDepths[] = {"8U", "8S", "16U", "16S", "32S", "32F", "64F", "16F"};
  std::string s = std::to_string(m.rows) + "x" + std::to_string(m.cols) + " " + kDepths[m.depth()];
  if (m.channels() > 1) s += "C" + std::to_string(m.channels());
  return s;
}

std::string views_column(const std::array<bool, kViewCount>& views) {
  std::string s;
  for (View v : kAllViews) {
    if (!s.empty()) s += ' ';
    std::string name = views[static_cast<size_t>(v)] ? view_name(v) : ".";
    name.resize(2, ' ');
    s += name;
  }
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

nlohmann::json user_to_json(const User& user) {
  nlohmann::json views = nlohmann::json::array();
  for (View v : kAllViews)
    if (user.views[static_cast<size_t>(v)]) views.push_back(view_name(v));
  return {{"id", user.id},
          {"label", user.label},
          {"views", views},
          {"scans", user.scans},
          {"created", format_utc(user.created)},
          {"first_seen", format_utc(user.first_seen)},
          {"last_seen", format_utc(user.last_seen)}};
}

nlohmann::json scan_to_json(const StoredScan& scan) {
  nlohmann::json j = {{"view", view_name(scan.view)},
                      {"quality", scan.quality},
                      {"image", !scan.image_png.empty()},
                      {"mask", !scan.mask_png.empty()},
                      {"descriptor", scan.descriptor},
                      {"descriptor_version", scan.descriptor_version},
                      {"features", describe_matrix(scan.features)},
                      {"time", format_utc(scan.time)}};
  if (scan.stored) j["stored"] = format_utc(*scan.stored);
  return j;
}

nlohmann::json event_to_json(const Event& event) {
  nlohmann::json j = {{"id", event.id}, {"kind", event_kind_name(event.kind)}, {"time", format_utc(event.time)}};
  if (event.user) j["user"] = *event.user;
  if (event.view) j["view"] = view_name(*event.view);
  if (event.score) j["score"] = *event.score;
  if (event.track) j["track"] = *event.track;
  if (!event.source.empty()) j["source"] = event.source;
  if (!event.sensor.empty()) j["sensor"] = event.sensor;
  if (event.logged) j["logged"] = format_utc(*event.logged);
  return j;
}

nlohmann::json features_to_json(const cv::Mat& features) {
  cv::Mat values;
  features.reshape(1, 1).convertTo(values, CV_64F);
  const std::string type = describe_matrix(features);
  return {{"type", type.substr(type.find(' ') + 1)},
          {"rows", features.rows},
          {"cols", features.cols},
          {"channels", features.channels()},
          {"values", std::vector<double>(values.begin<double>(), values.end<double>())}};
}

}  // namespace bodyrec
