// The meshes of OtherMeshesBenchmark: how one is made and described, and the survey set (more
// of VTK's sources, SurveyMeshes.cxx) that it runs through the default filters only.
#ifndef OtherMeshes_h
#define OtherMeshes_h

#include "vtkSmartPointer.h"

#include <functional>
#include <string>
#include <vector>

class vtkAlgorithm;
class vtkPolyData;

namespace meshlod
{
namespace benchmark
{
struct TestMesh
{
  std::string Name;
  std::string Description;
  std::function<vtkSmartPointer<vtkPolyData>()> Make;
};

/// The source's output triangulated and cleaned (exactly coincident points merged), then
/// linearly subdivided `subdivisions` times (none for 0).
vtkSmartPointer<vtkPolyData> Prepare(vtkAlgorithm* source, int subdivisions);

/// Twenty more shapes from VTK's sources (flat-faced solids, parametric surfaces with seams,
/// poles, spikes and self-intersections, open sheets, many separate pieces, needle triangles),
/// each of 50,000 to 640,000 triangles. vtkQuadricDecimation runs on every one of them (it did
/// not finish in minutes on a subdivided cone of 200 sides nor on vtkTessellatedBoxSource's box,
/// which are left out).
std::vector<TestMesh> SurveyMeshes();
} // namespace benchmark
} // namespace meshlod

#endif
