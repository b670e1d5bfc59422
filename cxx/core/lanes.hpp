// Lane types for code written once for one particle (T = double, ScalarLane) and for W
// particles at once (T = a GCC vector of W doubles, VectorLane<W>). A lane performs the
// IEEE operations of the scalar code in the same order, so the bits are the same
// (docs/DESIGN.md 5: vectorising across particles). Branches on a particle's data become
// selects that compute both arms.
//
// Everything here has internal linkage: a translation unit compiled for a wider
// instruction set (the *_avx2.cpp units) gets its own copies, never shared with the
// baseline units through the linker.
#pragma once
#include <immintrin.h>

#include <cmath>

// Vector types of these helpers never cross a call boundary of another unit.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace mpm3d {
namespace {

template <int W>
struct LaneTypes {
  typedef double D __attribute__((vector_size(8 * W)));
  typedef long M __attribute__((vector_size(8 * W)));
};

// Lane traits: the scalar one and the W-wide GCC vector.
struct ScalarLane {
  static constexpr int W = 1;
  static double splat(double x) { return x; }
  static double get(double x, int) { return x; }
  static void set(double& x, int, double v) { x = v; }
  static double sqrt(double x) { return std::sqrt(x); }
  static double select(bool m, double a, double b) { return m ? a : b; }
  static double load(const double* a) { return *a; }
  static void store(double* a, double x) { *a = x; }
  static double gather(const double* a, const int* idx) { return a[idx[0]]; }
  static double floor(double x) { return std::floor(x); }
};

template <int W_>
struct VectorLane {
  typedef typename LaneTypes<W_>::D D;
  typedef typename LaneTypes<W_>::M M;
  static constexpr int W = W_;
  static D splat(double x) { return D{} + x; }
  static double get(D x, int i) { return x[i]; }
  static void set(D& x, int i, double v) { x[i] = v; }
  // Correctly rounded per lane, as std::sqrt; the compiler emits the packed instruction
  // where the target has one.
  static D sqrt(D x) {
#if defined(__AVX512F__)
    if constexpr (W_ == 8) return (D)_mm512_sqrt_pd((__m512d)x);
#endif
#if defined(__AVX__)
    if constexpr (W_ == 4) return (D)_mm256_sqrt_pd((__m256d)x);
#endif
    D r;
    for (int i = 0; i < W_; i += 2) {
      __m128d pair = _mm_set_pd(x[i + 1], x[i]);
      pair = _mm_sqrt_pd(pair);
      r[i] = _mm_cvtsd_f64(pair);
      r[i + 1] = _mm_cvtsd_f64(_mm_unpackhi_pd(pair, pair));
    }
    return r;
  }
  template <class Mask>
  static D select(Mask m, D a, D b) { return m ? a : b; }
  static D load(const double* a) {
    D x;
    __builtin_memcpy(&x, a, sizeof x);
    return x;
  }
  static void store(double* a, D x) { __builtin_memcpy(a, &x, sizeof x); }
  // Exact (rounding to an integer is), as std::floor.
  static D floor(D x) {
#if defined(__AVX__)
    if constexpr (W_ == 4) return (D)_mm256_round_pd((__m256d)x, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
#endif
    D r;
    for (int i = 0; i < W_; ++i) r[i] = std::floor(x[i]);
    return r;
  }
  // Lane i from a[idx[i]].
  static D gather(const double* a, const int* idx) {
    D x;
    for (int i = 0; i < W_; ++i) x[i] = a[idx[i]];
    return x;
  }
};

}  // namespace
}  // namespace mpm3d
