// What one core of this CPU can do per cycle with 512-bit doubles: the clock (a chain of dependent
// integer adds, one cycle each), and the throughput of independent vmulpd, vaddpd, vdivpd and
// vsqrtpd, alone and mixed. Twelve independent accumulators hide every latency. Build with the
// host's instruction set: g++ -O2 -march=native -std=c++20 fp_throughput.cpp (needs AVX-512F).
#include <immintrin.h>

#include <chrono>
#include <cstdio>

namespace {

volatile double sink;

double seconds_of(auto&& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Cycles per iteration of `body` (12 independent zmm operations), best of five.
template <class Body>
double cycles_per_iteration(double clock_hz, long n, Body body) {
  double best = 1e30;
  for (int r = 0; r < 5; ++r) {
    __m512d a[12];
    for (auto& x : a) x = _mm512_set1_pd(1.0000001);
    const __m512d b = _mm512_set1_pd(0.9999999);
    __m512d a0 = a[0], a1 = a[1], a2 = a[2], a3 = a[3], a4 = a[4], a5 = a[5], a6 = a[6], a7 = a[7], a8 = a[8],
            a9 = a[9], a10 = a[10], a11 = a[11];
    const double s = seconds_of([&] {
      for (long i = 0; i < n; ++i) {
        body(a0, a1, a2, a3, a4, a5, a6, a7, a8, a9, a10, a11, b);
        asm volatile("" : "+v"(a0), "+v"(a1), "+v"(a2), "+v"(a3), "+v"(a4), "+v"(a5), "+v"(a6), "+v"(a7), "+v"(a8),
                     "+v"(a9), "+v"(a10), "+v"(a11));
      }
    });
    sink = _mm512_reduce_add_pd(_mm512_add_pd(_mm512_add_pd(_mm512_add_pd(a0, a1), _mm512_add_pd(a2, a3)),
                                              _mm512_add_pd(_mm512_add_pd(a4, a5), _mm512_add_pd(a6, a7)))) +
           _mm512_reduce_add_pd(_mm512_add_pd(_mm512_add_pd(a8, a9), _mm512_add_pd(a10, a11)));
    if (s / static_cast<double>(n) < best) best = s / static_cast<double>(n);
  }
  return best * clock_hz;
}

#define TWELVE(OP_A, OP_B)                                                                                   \
  [](__m512d& a0, __m512d& a1, __m512d& a2, __m512d& a3, __m512d& a4, __m512d& a5, __m512d& a6, __m512d& a7, \
     __m512d& a8, __m512d& a9, __m512d& a10, __m512d& a11, __m512d b) {                                      \
    a0 = OP_A(a0, b), a1 = OP_A(a1, b), a2 = OP_A(a2, b), a3 = OP_A(a3, b), a4 = OP_A(a4, b), a5 = OP_A(a5, b); \
    a6 = OP_B(a6, b), a7 = OP_B(a7, b), a8 = OP_B(a8, b), a9 = OP_B(a9, b), a10 = OP_B(a10, b);                \
    a11 = OP_B(a11, b);                                                                                       \
  }

__m512d sqrt_of(__m512d a, __m512d) { return _mm512_sqrt_pd(a); }

}  // namespace

int main() {
  double clock_hz = 0.0;
  for (int r = 0; r < 5; ++r) {
    const long n = 200000000;
    long x = 0;
    const double s = seconds_of([&] {
      for (long i = 0; i < n; ++i) asm volatile("add $1, %0\n\tadd $1, %0\n\tadd $1, %0\n\tadd $1, %0" : "+r"(x));
    });
    sink = static_cast<double>(x);
    if (4.0 * n / s > clock_hz) clock_hz = 4.0 * n / s;
  }
  std::printf("clock %.3f GHz (dependent integer adds)\n", clock_hz / 1e9);
  auto show = [&](const char* what, double cycles) {
    std::printf("%-16s %6.2f cycles per 12 zmm ops (%.2f ops per cycle)\n", what, cycles, 12.0 / cycles);
  };
  show("vmulpd", cycles_per_iteration(clock_hz, 20000000, TWELVE(_mm512_mul_pd, _mm512_mul_pd)));
  show("vaddpd", cycles_per_iteration(clock_hz, 20000000, TWELVE(_mm512_add_pd, _mm512_add_pd)));
  show("6 mul + 6 add", cycles_per_iteration(clock_hz, 20000000, TWELVE(_mm512_mul_pd, _mm512_add_pd)));
  show("vdivpd", cycles_per_iteration(clock_hz, 2000000, TWELVE(_mm512_div_pd, _mm512_div_pd)));
  show("vsqrtpd", cycles_per_iteration(clock_hz, 2000000, TWELVE(sqrt_of, sqrt_of)));
  show("6 div + 6 sqrt", cycles_per_iteration(clock_hz, 2000000, TWELVE(_mm512_div_pd, sqrt_of)));
}
