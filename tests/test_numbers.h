// test_numbers.h -- the constants the tests share, and bitwise equality of
// doubles (the tests that demand the same bits, not the same value). One
// definition each: rtb_tests is a unity build (CMakeLists.txt), where two
// files' definitions of the same name would meet.
#ifndef RTB_TESTS_TEST_NUMBERS_H
#define RTB_TESTS_TEST_NUMBERS_H

#include <cstring>
#include <limits>

inline constexpr double kTwoPi = 6.283185307179586476925;
inline constexpr double kInf = std::numeric_limits<double>::infinity();
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Same bits, so -0.0 != 0.0 and a NaN equals itself.
inline bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

#endif
