// The positional arguments of the benchmark programs that take numbers. A mistyped option would
// otherwise be read as 0 or ignored and start a run of many minutes: --help, or an argument
// that is not a positive whole number, prints the usage instead.
#ifndef BenchmarkArguments_h
#define BenchmarkArguments_h

#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace meshlod
{
namespace benchmark
{
/// Whether argv[1 .. numbers] (those given) are positive whole numbers in digits (what atoi and
/// atoll read in full: not "1e5", "0.5" or "inf") and, unless `more` is set, no argument follows
/// them. Otherwise prints "usage: <program> <usage>" (to stdout for -h or --help, exit code 0; to
/// stderr otherwise, exit code 2) and returns false with `exitCode`.
inline bool NumberArguments(
  int argc, char* argv[], int numbers, bool more, const char* usage, int& exitCode)
{
  const bool help =
    argc > 1 && (std::strcmp(argv[1], "-h") == 0 || std::strcmp(argv[1], "--help") == 0);
  bool valid = !help && (more || argc - 1 <= numbers);
  for (int i = 1; valid && i < argc && i <= numbers; ++i)
  {
    const std::size_t digits = std::strspn(argv[i], "0123456789");
    valid = digits > 0 && digits <= 15 && argv[i][digits] == '\0' && std::atoll(argv[i]) > 0;
  }
  if (valid)
  {
    return true;
  }
  std::fprintf(help ? stdout : stderr, "usage: %s %s\n", argv[0], usage);
  exitCode = help ? 0 : 2;
  return false;
}
} // namespace benchmark
} // namespace meshlod

#endif
