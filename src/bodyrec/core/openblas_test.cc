#include "bodyrec/core/openblas.h"

#include <dlfcn.h>

#include <cmath>
#include <cstdlib>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace bodyrec {
namespace {

TEST(OpenBlas, SwitchesOnlyFromTheSse3FallbackAndOnlyToWhatTheCpuHas) {
  EXPECT_EQ(better_openblas_core("Prescott", true, true), "SkylakeX");
  EXPECT_EQ(better_openblas_core("Prescott", true, false), "Haswell");
  EXPECT_EQ(better_openblas_core("Prescott", false, false), "");
  EXPECT_EQ(better_openblas_core("Haswell", true, true), "");   // a CPU OpenBLAS knows keeps its pick
  EXPECT_EQ(better_openblas_core("Zen", true, false), "");
  EXPECT_EQ(better_openblas_core("", true, true), "");          // not OpenBLAS
}

// The switch happens in a running OpenBLAS: after it, its matrix product must still be right.
TEST(OpenBlas, AfterChoosingTheKernelsMatrixProductsAreRight) {
  // This test program links no BLAS (nothing in bodyrec's core calls one): load the one dlib uses.
  if (openblas_core().empty()) dlopen("libblas.so.3", RTLD_NOW | RTLD_GLOBAL);
  if (openblas_core().empty()) GTEST_SKIP() << "the BLAS library here is not an OpenBLAS built for several CPUs";
  if (std::getenv("OPENBLAS_CORETYPE")) GTEST_SKIP() << "OPENBLAS_CORETYPE is set: the user's choice stands";
  const std::string core = choose_openblas_core();
  EXPECT_EQ(core, openblas_core());
  EXPECT_EQ(std::getenv("OPENBLAS_CORETYPE"), nullptr);  // the environment is left as it was
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) {
    EXPECT_NE(core, "Prescott");
  }

  using Sgemm = void(int, int, int, int, int, int, float, const float*, int, const float*, int, float, float*, int);
  const auto sgemm = reinterpret_cast<Sgemm*>(dlsym(RTLD_DEFAULT, "cblas_sgemm"));
  ASSERT_NE(sgemm, nullptr);
  const int m = 67, n = 39, k = 45;  // sizes that are no multiple of any kernel's block
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> value(-1.f, 1.f);
  std::vector<float> a(m * k), b(k * n), c(m * n, 0.f);
  for (float& x : a) x = value(rng);
  for (float& x : b) x = value(rng);
  sgemm(101 /* row-major */, 111 /* no transpose */, 111, m, n, k, 1.f, a.data(), k, b.data(), n, 0.f, c.data(), n);
  double worst = 0;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < n; ++j) {
      double want = 0;
      for (int t = 0; t < k; ++t) want += static_cast<double>(a[i * k + t]) * b[t * n + j];
      worst = std::max(worst, std::abs(want - c[i * n + j]));
    }
  EXPECT_LT(worst, 1e-4);
}

}  // namespace
}  // namespace bodyrec
