// What the benchmark programs share besides the methods themselves: the input meshes and the
// lookup of a registered method by its name.
#include "BenchmarkMethods.h"

#include "vtkCleanPolyData.h"
#include "vtkNew.h"
#include "vtkPolyData.h"

#include <cstdio>
#include <cstdlib>

namespace meshlod
{
namespace benchmark
{
vtkSmartPointer<vtkPolyData> MakeBenchmarkMesh(
  meshlod::testing::Field field, double triangles, int& resolution, vtkIdType& dropped)
{
  resolution = meshlod::testing::ResolutionForTriangles(field, triangles);
  vtkSmartPointer<vtkPolyData> surface = meshlod::testing::MakeIsosurface(field, resolution);
  // Flying edges makes coincident points where the field is exactly 0 at a grid vertex; a
  // zero-length edge gives vtkQuadricDecimation a non-finite cost (the likely cause of its
  // stop), while it reaches the target on the cleaned mesh.
  vtkNew<vtkCleanPolyData> clean;
  clean->SetInputData(surface);
  clean->PointMergingOn();
  clean->SetTolerance(0.0);
  clean->ConvertPolysToLinesOff();
  clean->ConvertLinesToPointsOff();
  clean->Update();
  auto cleaned = vtkSmartPointer<vtkPolyData>::New();
  cleaned->ShallowCopy(clean->GetOutput());
  dropped = surface->GetNumberOfPolys() - cleaned->GetNumberOfPolys();
  return cleaned;
}

const Method& FindMethod(const std::vector<Method>& methods, const std::string& name)
{
  for (const Method& method : methods)
  {
    if (method.Name == name)
    {
      return method;
    }
  }
  std::fprintf(stderr, "no method named '%s' is registered\n", name.c_str());
  std::exit(1);
}

} // namespace benchmark
} // namespace meshlod
