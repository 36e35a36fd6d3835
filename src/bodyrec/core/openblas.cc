#include "bodyrec/core/openblas.h"

#include <dlfcn.h>

#include <cstdlib>

namespace bodyrec {
namespace {

template <typename F>
F* blas_function(const char* name) {
  return reinterpret_cast<F*>(dlsym(RTLD_DEFAULT, name));
}

}  // namespace

std::string openblas_core() {
  // gotoblas_corename exists only in builds for several CPUs (DYNAMIC_ARCH), the ones that can switch.
  const auto corename = blas_function<char*()>("gotoblas_corename");
  if (!corename) return "";
  const char* name = corename();
  return name ? name : "";
}

std::string better_openblas_core(const std::string& picked, bool avx2_fma, bool avx512) {
  if (picked != "Prescott") return "";
  if (avx512) return "SkylakeX";
  if (avx2_fma) return "Haswell";
  return "";
}

std::string choose_openblas_core() {
  const std::string picked = openblas_core();
  if (picked.empty() || std::getenv("OPENBLAS_CORETYPE")) return picked;
  __builtin_cpu_init();
  const bool avx2_fma = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  const bool avx512 = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
                      __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512vl");
  const std::string better = better_openblas_core(picked, avx2_fma, avx512);
  const auto quit = blas_function<void()>("gotoblas_dynamic_quit");
  const auto init = blas_function<void()>("gotoblas_dynamic_init");
  if (better.empty() || !quit || !init) return picked;
  // OpenBLAS picks its kernels once, at load time, from OPENBLAS_CORETYPE or the CPU's model; forgetting
  // the pick and picking again with the variable set switches them. The variable is removed afterwards,
  // leaving the environment as it was.
  setenv("OPENBLAS_CORETYPE", better.c_str(), 1);
  quit();
  init();
  unsetenv("OPENBLAS_CORETYPE");
  return openblas_core();
}

OneBlasThread::OneBlasThread() {
  set_ = blas_function<void(int)>("openblas_set_num_threads");
  const auto get = blas_function<int()>("openblas_get_num_threads");
  if (!set_ || !get) {
    set_ = nullptr;
    return;
  }
  before_ = get();
  set_(1);
}

OneBlasThread::~OneBlasThread() {
  if (set_) set_(before_);
}

}  // namespace bodyrec
