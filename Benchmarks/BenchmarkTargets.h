// The project's numeric targets for its two simplification filters, checked on the rows of one
// run of MeshLODBenchmark: for each target the range measured over the run's meshes and target
// sizes, where the worst value is, whether every value meets it, and for a target missed the
// reason, so that RESULTS.md states its shortfalls itself instead of leaving them to be worked
// out from the ratios.
#ifndef BenchmarkTargets_h
#define BenchmarkTargets_h

#include <cstdio>
#include <functional>
#include <string>
#include <vector>

namespace meshlod
{
namespace benchmark
{
/// One number as printf's `format` writes it (the report's tables and this section alike).
inline std::string Format(const char* format, double value)
{
  char text[64];
  std::snprintf(text, sizeof(text), format, value);
  return text;
}

/// What the benchmark measured for one method on one mesh, with one thread count, at one target
/// size. A hierarchy method's time and memory are those of its whole hierarchy, the same in each
/// of its target sizes' rows.
struct Measurement
{
  double Seconds = 0.0;
  double Hausdorff = 0.0; // % of the bounding-box diagonal
  double Rms = 0.0;
  double BytesPerTriangle = -1.0; // peak memory growth per input triangle, -1 unknown
};

/// Fills `result` with the measurement of `method` (the label of its table rows) on mesh
/// `mesh` with `threads` threads at `fraction` of the input's triangles; false when that run is
/// not in the benchmark (a method or thread count left out by the arguments).
using FindMeasurement = std::function<bool(
  size_t mesh, const std::string& method, int threads, double fraction, Measurement& result)>;

/// The Markdown section "Targets": every target of vtkTriangleCollapseDecimation (against
/// vtkQuadricDecimation and vtkDecimatePro) and of vtkVertexClusterOctree (against
/// vtkQuadricClustering) checked on meshes 0 .. meshLabels.size() - 1 and every fraction;
/// times and memory are compared at the largest fraction (the reference's largest target
/// alone against the whole hierarchy). Targets with no measurement in the run are left out.
std::string TargetsReport(const std::vector<std::string>& meshLabels,
  const std::vector<double>& fractions,
  const FindMeasurement& find);
}
}

#endif
