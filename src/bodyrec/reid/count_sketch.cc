#include "bodyrec/reid/count_sketch.h"

#include <algorithm>

#include <opencv2/core.hpp>

namespace bodyrec {
namespace {

// SplitMix64's finaliser (Steele et al. 2014): a fixed, well-mixed 64-bit hash, the same everywhere
// (std:: distributions are not specified bit for bit across standard libraries).
uint64_t mix(uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

}  // namespace

CountSketch::CountSketch(int input_length, int output_length, uint64_t seed)
    : output_length_(output_length),
      bucket_(static_cast<size_t>(std::max(input_length, 0))),
      sign_(bucket_.size()) {
  CV_Assert(output_length > 0 && output_length <= input_length);
  for (size_t i = 0; i < bucket_.size(); ++i) {
    const uint64_t h = mix(mix(seed) ^ i);
    bucket_[i] = static_cast<int>((h >> 1) % static_cast<uint64_t>(output_length));
    sign_[i] = (h & 1) ? -1.0f : 1.0f;
  }
}

void CountSketch::apply(const float* in, float* out) const {
  std::fill(out, out + output_length_, 0.0f);
  for (size_t i = 0; i < bucket_.size(); ++i) out[bucket_[i]] += sign_[i] * in[i];
}

std::vector<float> CountSketch::apply(const std::vector<float>& in) const {
  CV_Assert(static_cast<int>(in.size()) == input_length());
  std::vector<float> out(static_cast<size_t>(output_length_));
  apply(in.data(), out.data());
  return out;
}

}  // namespace bodyrec
