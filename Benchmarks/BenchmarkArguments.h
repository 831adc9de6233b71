// The arguments of the benchmark programs: positional numbers, and the isosurfaces to make. A
// mistyped option would otherwise be read as 0 or ignored and start a run of many minutes:
// --help, or an argument that is not a positive whole number, prints the usage instead.
#ifndef BenchmarkArguments_h
#define BenchmarkArguments_h

#include "MeshLODTestMeshes.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

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

/// An isosurface to make, "field:triangles" (e.g. gyroid:600000: the field and about how many
/// triangles, at least 100). Otherwise prints what is wrong and returns false.
inline bool MeshArgument(const std::string& text, testing::Field& field, double& triangles)
{
  const std::size_t colon = text.find(':');
  triangles = colon == std::string::npos ? 0.0 : std::atof(text.c_str() + colon + 1);
  if (colon == std::string::npos || !testing::FieldFromName(text.substr(0, colon), field) ||
    !(triangles >= 100.0))
  {
    std::fprintf(stderr, "bad mesh %s (want field:triangles, e.g. gyroid:600000)\n", text.c_str());
    return false;
  }
  return true;
}

/// The isosurfaces argv[first], argv[first + 1], ... ask for (see MeshArgument), appended to
/// `meshes`; false at the first bad one.
inline bool MeshArguments(int argc, char* argv[], int first,
  std::vector<std::pair<testing::Field, double>>& meshes)
{
  for (int i = first; i < argc; ++i)
  {
    testing::Field field;
    double triangles;
    if (!MeshArgument(argv[i], field, triangles))
    {
      return false;
    }
    meshes.emplace_back(field, triangles);
  }
  return true;
}
} // namespace benchmark
} // namespace meshlod

#endif
