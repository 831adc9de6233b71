// The methods the benchmark compares, kept as a small registry so that adding one is a single
// entry: VTK's decimators in VTKMethods.cxx, MeshLOD's own filters in MeshLODMethods.cxx.
//
// A method is either
// - a single-output method: Prepare(input, target) runs untimed (e.g. to search a grid
//   resolution that gives the target count) and returns the job that is timed, or
// - a hierarchy method: Hierarchy(input, targets) is timed once as a whole and returns one output
//   per target (the level the method offers for that triangle count); every level is then
//   measured against the input at its own triangle count.
#ifndef BenchmarkMethods_h
#define BenchmarkMethods_h

#include "MeshLODTestMeshes.h"
#include "vtkSmartPointer.h"
#include "vtkType.h"

#include <functional>
#include <string>
#include <vector>

class vtkPolyData;

namespace meshlod
{
namespace benchmark
{
/// The timed part of a single-output run.
using Job = std::function<vtkSmartPointer<vtkPolyData>()>;

struct Method
{
  std::string Name;      // the table's row label
  std::string Settings;  // the settings used, listed under the tables
  bool Parallel = false; // uses vtkSMPTools: also run with two threads
  /// Skip inputs with more triangles than this (0: no limit), for methods too slow for the
  /// largest meshes; stated under the tables.
  vtkIdType MaximumInputTriangles = 0;

  /// Single-output methods: untimed set-up for one input and target triangle count; returns the
  /// job to time.
  std::function<Job(vtkPolyData* input, vtkIdType targetTriangles)> Prepare;

  /// Hierarchy methods (leave Prepare empty): one timed run making every level; returns one
  /// output per entry of targetTriangles, in the same order.
  std::function<std::vector<vtkSmartPointer<vtkPolyData>>(
    vtkPolyData* input, const std::vector<vtkIdType>& targetTriangles)>
    Hierarchy;
};

/// A single-output method with nothing to prepare: decimate(input, target) is timed as a whole.
Method SimpleMethod(const std::string& name,
  const std::string& settings,
  bool parallel,
  std::function<vtkSmartPointer<vtkPolyData>(vtkPolyData*, vtkIdType)> decimate);

/// Finds a setting x > 0 whose output has about `target` triangles, for a method whose triangle
/// count grows with x roughly like a power of x (a grid resolution, an inverse tolerance).
/// `count(x)` runs the method; the search is untimed. Tries are rounded to integers when
/// `integer` is set. Returns the best x tried (closest count in ratio).
double SearchSetting(
  double first, vtkIdType target, bool integer, const std::function<vtkIdType(double x)>& count);

/// The benchmark's input: the flying-edges isosurface of `field` at the resolution that gives
/// about `triangles` triangles, cleaned (exactly coincident points merged, the triangles that
/// collapse dropped: on the uncleaned 2.3M-triangle gyroid vtkQuadricDecimation stops after
/// about 2000 collapses). Gives the volume's resolution and the number of triangles dropped.
/// (BenchmarkHarness.cxx)
vtkSmartPointer<vtkPolyData> MakeBenchmarkMesh(
  meshlod::testing::Field field, double triangles, int& resolution, vtkIdType& dropped);

/// The registered method of that name; a program asking for one that is not there stops with
/// an error. (BenchmarkHarness.cxx)
const Method& FindMethod(const std::vector<Method>& methods, const std::string& name);

/// VTK's decimators (VTKMethods.cxx).
void RegisterVTKMethods(std::vector<Method>& methods);

/// MeshLOD's filters (MeshLODMethods.cxx).
void RegisterMeshLODMethods(std::vector<Method>& methods);

} // namespace benchmark
} // namespace meshlod

#endif
