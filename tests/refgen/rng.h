// rng.h -- the generator's own random stream (splitmix64 + Box-Muller), so
// that a seed gives the same records with every standard library.
#ifndef RTB_TESTS_REFGEN_RNG_H
#define RTB_TESTS_REFGEN_RNG_H

#include <cmath>
#include <cstdint>

namespace refgen {

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : s_(seed * 0x9E3779B97F4A7C15ull + 0x2545F4914F6CDD1Dull) {}
  // Uniform on [0, 1).
  double uniform() { return (double)(next() >> 11) * (1.0 / 9007199254740992.0); }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  double log_uniform(double lo, double hi) { return lo * std::pow(hi / lo, uniform()); }
  int integer(int lo, int hi) { return lo + (int)(uniform() * (hi - lo + 1)); }  // lo..hi
  double sign() { return uniform() < 0.5 ? -1.0 : 1.0; }
  // Standard normal (Box-Muller, one value per call).
  double normal() {
    const double u1 = 1.0 - uniform(), u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
  }

 private:
  std::uint64_t next() {
    std::uint64_t z = (s_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  std::uint64_t s_;
};

}  // namespace refgen

#endif
