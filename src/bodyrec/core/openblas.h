// OpenBLAS, Debian's BLAS behind dlib's network training (train-shape), controlled at run time. Its
// functions are found through dlsym, so that another BLAS library is left alone.
#pragma once

#include <string>

namespace bodyrec {

// The kernels OpenBLAS picked for this CPU ("Haswell", "SkylakeX", "Prescott"...), or "" when the BLAS in
// the process is not an OpenBLAS built for several CPUs (Debian's is).
std::string openblas_core();

// The kernels to switch to from `picked`. OpenBLAS 0.3.21 (Debian 12) falls back to its SSE3 kernels
// ("Prescott") on Intel CPUs newer than it (family 6 model 207, a 2023 Xeon, among them), which made a
// network's training 20 % slower (docs/benchmarks.md). Returns "SkylakeX" when the CPU has AVX-512 (F, DQ,
// BW, VL), else "Haswell" when it has AVX2 and FMA, else "": keep what it picked. Any pick other than
// "Prescott" is kept too.
std::string better_openblas_core(const std::string& picked, bool avx2_fma, bool avx512);

// Switches OpenBLAS to better_openblas_core() for this CPU, unless OPENBLAS_CORETYPE is set (the user's
// choice stands). Call it before any BLAS call and while no other thread can make one (the CLI's main
// does). Returns the kernels in use afterwards ("" when not OpenBLAS).
std::string choose_openblas_core();

// While alive, OpenBLAS runs each call on one thread (the former setting is restored afterwards): when
// several dlib trainers run side by side, one per core, OpenBLAS must not split each of their calls over
// every core too (that ran a pair of networks over 3.5x longer).
class OneBlasThread {
 public:
  OneBlasThread();
  ~OneBlasThread();
  OneBlasThread(const OneBlasThread&) = delete;
  OneBlasThread& operator=(const OneBlasThread&) = delete;

 private:
  void (*set_)(int) = nullptr;
  int before_ = 1;
};

}  // namespace bodyrec
