// The eight partial-scan views of thesis Ch6 (3D PSMs): one background-removed image of a person per
// body orientation. Shared vocabulary of orientation (reid/orientation*), the gallery (store/) and the
// matchers: a view is stored and printed by its short name.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace bodyrec {

// Thesis order. The numeric values are stored in galleries: never renumber.
enum class View : int { F = 0, FR = 1, FL = 2, SR = 3, SL = 4, B = 5, BR = 6, BL = 7 };

constexpr int kViewCount = 8;
constexpr std::array<View, kViewCount> kAllViews = {View::F,  View::FR, View::FL, View::SR,
                                                    View::SL, View::B,  View::BR, View::BL};

// "F", "FR", ... "BL".
const char* view_name(View view);
// Inverse of view_name (case-sensitive); nullopt for anything else.
std::optional<View> parse_view(const std::string& name);
// The views the thesis also searches for a match (digest Ch6, complementary pairs F-FR, B-BR, FR-FL,
// SR-SL, BR-BL, taken both ways): F {FR}, FR {F, FL}, FL {FR}, SR {SL}, SL {SR}, B {BR}, BR {B, BL},
// BL {BR}.
std::vector<View> complementary_views(View view);

}  // namespace bodyrec
