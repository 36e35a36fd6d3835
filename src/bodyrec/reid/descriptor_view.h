// A read-only view of a descriptor's floats (a std::vector<float>, or a row stored in the gallery), so
// the gallery's scans are compared where they lie, without a copy per comparison.
#pragma once

#include <cstddef>
#include <vector>

namespace bodyrec {

struct DescriptorView {
  const float* data = nullptr;
  size_t size = 0;
  DescriptorView() = default;
  DescriptorView(const float* d, size_t n) : data(d), size(n) {}
  DescriptorView(const std::vector<float>& v) : data(v.data()), size(v.size()) {}  // NOLINT: implicit on purpose
  const float* begin() const { return data; }
  const float* end() const { return data + size; }
  std::vector<float> to_vector() const { return {begin(), end()}; }
};

}  // namespace bodyrec
