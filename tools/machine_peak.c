/* The machine's limits for docs/PERFORMANCE.md ("Distance to the machine's limit"): the
   double-precision add and multiply rate of one core with 256-bit AVX2 and no fused
   multiply-add (the bitwise contract rules it out), 12 independent chains of each so that
   latency does not bound it; and the bandwidth of a triad a = b + s c at sizes from L2 to
   memory. Build and run: gcc -O3 -mavx2 -ffp-contract=off tools/machine_peak.c -o peak && ./peak */
#include <immintrin.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

int main(void) {
  enum { kChains = 12 };
  __m256d add[kChains], mul[kChains];
  const __m256d step = _mm256_set1_pd(1e-9), factor = _mm256_set1_pd(0.999999999);
  for (int i = 0; i < kChains; i++) {
    add[i] = _mm256_set1_pd(i);
    mul[i] = _mm256_set1_pd(1.0 + i);
  }
  const long rounds = 20000000;
  double t0 = now();
  for (long k = 0; k < rounds; k++)
    for (int i = 0; i < kChains; i++) {
      add[i] = _mm256_add_pd(add[i], step);
      mul[i] = _mm256_mul_pd(mul[i], factor);
    }
  double t = now() - t0, sink = 0.0;
  for (int i = 0; i < kChains; i++) {
    double b[4];
    _mm256_storeu_pd(b, _mm256_add_pd(add[i], mul[i]));
    sink += b[0];
  }
  printf("add+mul, 256-bit, no FMA: %.2f GFLOP/s (%g)\n", rounds * kChains * 2.0 * 4 / t / 1e9, sink);
  // Divides and square roots, 256-bit, independent chains (the stress returns' and the
  // G2P's w / m): their own rate, far under the add and multiply one.
  __m256d dv[kChains], sq[kChains];
  const __m256d divisor = _mm256_set1_pd(1.000000001);
  for (int i = 0; i < kChains; i++) {
    dv[i] = _mm256_set1_pd(1.0 + i);
    sq[i] = _mm256_set1_pd(2.0 + i);
  }
  const long drounds = rounds / 8;
  t0 = now();
  for (long k = 0; k < drounds; k++)
    for (int i = 0; i < kChains; i++) dv[i] = _mm256_div_pd(dv[i], divisor);
  t = now() - t0;
  const double div_rate = drounds * kChains * 4.0 / t / 1e9;
  t0 = now();
  for (long k = 0; k < drounds; k++)
    for (int i = 0; i < kChains; i++) sq[i] = _mm256_sqrt_pd(sq[i]);
  t = now() - t0;
  for (int i = 0; i < kChains; i++) {
    double b[4];
    _mm256_storeu_pd(b, _mm256_add_pd(dv[i], sq[i]));
    sink += b[0];
  }
  printf("divide, 256-bit: %.2f G/s; square root, 256-bit: %.2f G/s (%g)\n", div_rate,
         drounds * kChains * 4.0 / t / 1e9, sink);
  const size_t sizes[] = {1u << 14, 1u << 17, 1u << 20, 1u << 23};
  for (int z = 0; z < 4; z++) {
    const size_t n = sizes[z];
    double *a = aligned_alloc(64, n * 8), *b = aligned_alloc(64, n * 8), *c = aligned_alloc(64, n * 8);
    for (size_t i = 0; i < n; i++) {
      a[i] = 0.0;
      b[i] = (double)i;
      c[i] = 1.0;
    }
    const long reps = (long)(4e9 / (n * 24.0)) + 1;
    t0 = now();
    for (long r = 0; r < reps; r++) {
      for (size_t i = 0; i < n; i++) a[i] = b[i] + 0.5 * c[i];
      __asm__ volatile("" : : "r"(a) : "memory");
    }
    t = now() - t0;
    printf("triad, %6zu KB an array: %.1f GB/s (%g)\n", n * 8 / 1024, reps * n * 24.0 / t / 1e9, a[n / 2]);
    free(a);
    free(b);
    free(c);
  }
  return 0;
}
