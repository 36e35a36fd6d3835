// A count sketch (Charikar et al. 2002; "feature hashing", Weinberger et al. 2009): a fixed random linear
// map from n values to k < n that adds each input, with a random sign, into one of k outputs. Inner
// products are kept in expectation, with an error that shrinks as 1/sqrt(k). The map is a pure function
// of (seed, n, k) computed from an explicit hash, so nothing of it is stored: a model trained on sketched
// features stores k rows of projection instead of n, and any build on any platform sketches alike.
#pragma once

#include <cstdint>
#include <vector>

namespace bodyrec {

class CountSketch {
 public:
  // REQUIRES 0 < output_length <= input_length.
  CountSketch(int input_length, int output_length, uint64_t seed);

  int input_length() const { return static_cast<int>(bucket_.size()); }
  int output_length() const { return output_length_; }

  // out[bucket(i)] += sign(i) * in[i] over the input_length() values at `in`; writes output_length()
  // values at `out` (zeroed first).
  void apply(const float* in, float* out) const;
  std::vector<float> apply(const std::vector<float>& in) const;

 private:
  int output_length_;
  std::vector<int> bucket_;   // per input index
  std::vector<float> sign_;   // +1 or -1 per input index
};

}  // namespace bodyrec
