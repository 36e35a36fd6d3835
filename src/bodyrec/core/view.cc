#include "bodyrec/core/view.h"

namespace bodyrec {

namespace {
constexpr std::array<const char*, kViewCount> kNames = {"F", "FR", "FL", "SR", "SL", "B", "BR", "BL"};
}

const char* view_name(View view) { return kNames.at(static_cast<size_t>(view)); }

std::optional<View> parse_view(const std::string& name) {
  for (View v : kAllViews)
    if (name == view_name(v)) return v;
  return std::nullopt;
}

std::vector<View> complementary_views(View view) {
  switch (view) {
    case View::F: return {View::FR};
    case View::FR: return {View::F, View::FL};
    case View::FL: return {View::FR};
    case View::SR: return {View::SL};
    case View::SL: return {View::SR};
    case View::B: return {View::BR};
    case View::BR: return {View::B, View::BL};
    case View::BL: return {View::BR};
  }
  return {};
}

}  // namespace bodyrec
