// CHECK macros for the C++ tests: a failed check prints file:line, the expression and the values,
// and the test keeps going, so one run reports every failure. Each test returns
// meshlod::testing::Result() from its main function.
#ifndef MeshLODTestCheck_h
#define MeshLODTestCheck_h

#include <cstdlib>
#include <cmath>
#include <iostream>
#include <type_traits>

namespace meshlod
{
namespace testing
{
inline int& FailureCount()
{
  static int failures = 0;
  return failures;
}

inline int Result()
{
  if (FailureCount() > 0)
  {
    std::cerr << FailureCount() << " check(s) failed\n";
    return EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}
// Enumerations print as their number.
template <typename T>
auto Printable(const T& value)
{
  if constexpr (std::is_enum<T>::value)
  {
    return static_cast<long long>(value);
  }
  else
  {
    return value;
  }
}
} // namespace testing
} // namespace meshlod

#define MESHLOD_CHECK(condition)                                                                   \
  do                                                                                               \
  {                                                                                                \
    if (!(condition))                                                                              \
    {                                                                                              \
      std::cerr << __FILE__ << ":" << __LINE__ << ": CHECK failed: " #condition "\n";              \
      ++meshlod::testing::FailureCount();                                                          \
    }                                                                                              \
  } while (false)

#define MESHLOD_CHECK_OP(a, op, b)                                                                 \
  do                                                                                               \
  {                                                                                                \
    const auto meshlodCheckA = (a);                                                                \
    const auto meshlodCheckB = (b);                                                                \
    if (!(meshlodCheckA op meshlodCheckB))                                                         \
    {                                                                                              \
      std::cerr << __FILE__ << ":" << __LINE__ << ": CHECK failed: " #a " " #op " " #b " (" \
                << meshlod::testing::Printable(meshlodCheckA) << " vs "                            \
                << meshlod::testing::Printable(meshlodCheckB) << ")\n";                              \
      ++meshlod::testing::FailureCount();                                                          \
    }                                                                                              \
  } while (false)

#define MESHLOD_CHECK_EQ(a, b) MESHLOD_CHECK_OP(a, ==, b)
#define MESHLOD_CHECK_LE(a, b) MESHLOD_CHECK_OP(a, <=, b)
#define MESHLOD_CHECK_LT(a, b) MESHLOD_CHECK_OP(a, <, b)
#define MESHLOD_CHECK_GE(a, b) MESHLOD_CHECK_OP(a, >=, b)
#define MESHLOD_CHECK_GT(a, b) MESHLOD_CHECK_OP(a, >, b)
/// |a - b| <= tolerance.
#define MESHLOD_CHECK_NEAR(a, b, tolerance) MESHLOD_CHECK_LE(std::abs((a) - (b)), tolerance)

#endif
