// Holds OpenMP to one thread on the calling thread for a scope, then puts back the caller's setting (it may
// be an application's own). oneDNN parallelises with OpenMP and fixes a primitive's thread count when the
// primitive is made: make and run primitives under this so that several run side by side, one per thread,
// instead of each starting a team over every core whose spinning threads fight the others for the cores
// (two processes fitting on two cores: 11 ms per person each instead of 3; docs/benchmarks.md).
#pragma once

#include <omp.h>

namespace bodyrec {

class OneOmpThread {
 public:
  OneOmpThread() : before_(omp_get_max_threads()) { omp_set_num_threads(1); }
  ~OneOmpThread() { omp_set_num_threads(before_); }
  OneOmpThread(const OneOmpThread&) = delete;
  OneOmpThread& operator=(const OneOmpThread&) = delete;

 private:
  int before_;
};

}  // namespace bodyrec
