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

// Checks a condition; on failure reports it and then runs `onFailure`, inside the macro's
// do-while: `return` leaves the calling function, but `continue` or `break` would only end the
// macro, not the caller's loop (write those out).
#define MESHLOD_CHECK_THEN(condition, onFailure)                                                   \
  do                                                                                               \
  {                                                                                                \
    if (!(condition))                                                                              \
    {                                                                                              \
      std::cerr << __FILE__ << ":" << __LINE__ << ": CHECK failed: " #condition "\n";              \
      ++meshlod::testing::FailureCount();                                                          \
      onFailure;                                                                                   \
    }                                                                                              \
  } while (false)

#define MESHLOD_CHECK(condition) MESHLOD_CHECK_THEN(condition, (void)0)
/// The condition holds, or the check fails and the calling (void) function returns: for what
/// the rest of a test relies on, such as a level that must exist before it is read.
#define MESHLOD_REQUIRE(condition) MESHLOD_CHECK_THEN(condition, return)

// Checks a op b; on failure reports it and then runs `onFailure` (as MESHLOD_CHECK_THEN).
#define MESHLOD_CHECK_OP_THEN(a, op, b, onFailure)                                                 \
  do                                                                                               \
  {                                                                                                \
    const auto meshlodCheckA = (a);                                                                \
    const auto meshlodCheckB = (b);                                                                \
    if (!(meshlodCheckA op meshlodCheckB))                                                         \
    {                                                                                              \
      std::cerr << __FILE__ << ":" << __LINE__ << ": CHECK failed: " #a " " #op " " #b " ("        \
                << meshlod::testing::Printable(meshlodCheckA) << " vs "                            \
                << meshlod::testing::Printable(meshlodCheckB) << ")\n";                           \
      ++meshlod::testing::FailureCount();                                                          \
      onFailure;                                                                                   \
    }                                                                                              \
  } while (false)

#define MESHLOD_CHECK_OP(a, op, b) MESHLOD_CHECK_OP_THEN(a, op, b, (void)0)
/// a == b, or the check fails and the calling (void) function returns: for what the rest of a
/// test relies on, such as a hierarchy's number of levels before the levels are read.
#define MESHLOD_REQUIRE_EQ(a, b) MESHLOD_CHECK_OP_THEN(a, ==, b, return)

#define MESHLOD_CHECK_EQ(a, b) MESHLOD_CHECK_OP(a, ==, b)
#define MESHLOD_CHECK_LE(a, b) MESHLOD_CHECK_OP(a, <=, b)
#define MESHLOD_CHECK_LT(a, b) MESHLOD_CHECK_OP(a, <, b)
#define MESHLOD_CHECK_GE(a, b) MESHLOD_CHECK_OP(a, >=, b)
#define MESHLOD_CHECK_GT(a, b) MESHLOD_CHECK_OP(a, >, b)
/// |a - b| <= tolerance.
#define MESHLOD_CHECK_NEAR(a, b, tolerance) MESHLOD_CHECK_LE(std::abs((a) - (b)), tolerance)

#endif
