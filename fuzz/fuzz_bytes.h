// fuzz_bytes.h -- turns a fuzzer's byte string into typed values, front to
// back. An exhausted input reads as zeros, so every byte string is a valid
// program for a target (libFuzzer mutates bytes, not structure).
#ifndef RTB_FUZZ_BYTES_H
#define RTB_FUZZ_BYTES_H

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace rtb_fuzz {

class Bytes {
 public:
  Bytes(const uint8_t *data, size_t size) : d_(data), n_(size) {}
  bool empty() const { return n_ == 0; }
  uint8_t u8() {
    if (n_ == 0) return 0;
    --n_;
    return *d_++;
  }
  uint32_t u32() {
    uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v = v << 8 | u8();
    return v;
  }
  // Uniform in [0, 1) with 32 bits of resolution.
  double unit() { return u32() * (1.0 / 4294967296.0); }
  // Log-uniform in [lo, hi] (lo > 0).
  double log_uniform(double lo, double hi) {
    return std::exp(std::log(lo) + unit() * (std::log(hi) - std::log(lo)));
  }
  // Any bit pattern: NaN, infinities, subnormals, huge values.
  double raw_double() {
    uint64_t b = 0;
    for (int i = 0; i < 8; ++i) b = b << 8 | u8();
    double v;
    std::memcpy(&v, &b, sizeof v);
    return v;
  }

 private:
  const uint8_t *d_;
  size_t n_;
};

// Stops the process with a message: a broken promise is a crash for the
// fuzzer and for the replay driver alike.
[[noreturn]] inline void fail(const char *what) {
  std::fprintf(stderr, "fuzz property violated: %s\n", what);
  std::abort();
}

}  // namespace rtb_fuzz

#endif
