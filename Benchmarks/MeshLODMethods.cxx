// MeshLOD's own filters in the benchmark. Each filter is one `methods.push_back(...)` below; the
// harness runs every registered method on the same meshes and targets as VTK's decimators and
// compares it with vtkQuadricDecimation. See BenchmarkMethods.h for the two kinds of method, and
// VTKMethods.cxx for examples: a plain run (vtkQuadricDecimation), an untimed search of a setting
// (vtkQuadricClustering) and a hierarchy (vtkQuadricDecimation chained).
//
// A hierarchy filter is registered with Hierarchy set: time one Update() making all the levels,
// then hand back, for each target, the level nearest to it, e.g.
//
//   Method m;
//   m.Name = "vtkTriangleCollapseDecimation";
//   m.Settings = "...";
//   m.Parallel = true;
//   m.Hierarchy = [](vtkPolyData* input, const std::vector<vtkIdType>& targets) { ... };
//   methods.push_back(m);
//
// No MeshLOD filter is registered yet: they land in their own branches.
#include "BenchmarkMethods.h"

#include "vtkSetGet.h" // vtkNotUsed

namespace meshlod
{
namespace benchmark
{
void RegisterMeshLODMethods(std::vector<Method>& vtkNotUsed(methods)) {}
} // namespace benchmark
} // namespace meshlod
