// What both hierarchy filters make of inputs a pipeline can hand them besides a plain float or
// double surface: composite data (an error that says what to do, not a hierarchy nested in a
// hierarchy, which the pipeline's block-by-block execution made) and integer points (levels in
// double, not collapse points and geomorph frames truncated to integers).
#include "vtkLODGeomorph.h"
#include "vtkTriangleCollapseDecimation.h"
#include "vtkVertexClusterOctree.h"

#include "MeshLODTestCheck.h"
#include "MeshLODTestMeshes.h"

#include "vtkExecutive.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkTestErrorObserver.h"

#include <cmath>
#include <iostream>
#include <string>

namespace
{
using namespace meshlod;

// The number of coordinates of `poly` that are not whole numbers.
vtkIdType FractionalCoordinates(vtkPolyData* poly)
{
  vtkIdType count = 0;
  for (vtkIdType p = 0; p < poly->GetNumberOfPoints(); ++p)
  {
    double x[3];
    poly->GetPoint(p, x);
    for (int k = 0; k < 3; ++k)
    {
      count += x[k] != std::round(x[k]) ? 1 : 0;
    }
  }
  return count;
}

template <typename Filter>
void TestComposite(const char* name)
{
  vtkSmartPointer<vtkPolyData> sphere = testing::MakeIcosphere(2);
  vtkNew<vtkMultiBlockDataSet> blocks;
  blocks->SetBlock(0, sphere);
  blocks->SetBlock(1, sphere);
  vtkNew<vtkTest::ErrorObserver> observer;
  vtkNew<Filter> filter;
  filter->AddObserver(vtkCommand::ErrorEvent, observer);
  filter->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, observer);
  filter->SetInputData(blocks);
  filter->Update();
  std::cout << name << ": composite input refused\n";
  MESHLOD_CHECK(observer->GetErrorMessage().find(
                  "The input is composite data (a vtkMultiBlockDataSet)") != std::string::npos);
  MESHLOD_CHECK_EQ(filter->GetHierarchy()->GetNumberOfBlocks(), 0u);

  // The same filter on one surface afterwards: a hierarchy again.
  filter->SetInputData(sphere);
  filter->Update();
  MESHLOD_CHECK_GT(filter->GetHierarchy()->GetNumberOfBlocks(), 1u);
}

// Points in integer units (a sphere of radius 1000): every level in double, the coarse levels'
// points off the integer grid, and so is a geomorph frame between levels 0 and 1.
template <typename Filter>
void TestIntegerPoints(const char* name)
{
  vtkSmartPointer<vtkPolyData> sphere = testing::MakeIcosphere(3);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToInt();
  points->SetNumberOfPoints(sphere->GetNumberOfPoints());
  for (vtkIdType p = 0; p < sphere->GetNumberOfPoints(); ++p)
  {
    double x[3];
    sphere->GetPoint(p, x);
    points->SetPoint(p, std::round(1000.0 * x[0]), std::round(1000.0 * x[1]),
      std::round(1000.0 * x[2]));
  }
  vtkNew<vtkPolyData> mesh;
  mesh->SetPoints(points);
  mesh->SetPolys(sphere->GetPolys());
  vtkNew<Filter> filter;
  filter->SetInputData(mesh);
  filter->Update();
  vtkMultiBlockDataSet* h = filter->GetHierarchy();
  MESHLOD_CHECK_GT(h->GetNumberOfBlocks(), 1u);
  for (unsigned int i = 0; i < h->GetNumberOfBlocks(); ++i)
  {
    auto* level = vtkPolyData::SafeDownCast(h->GetBlock(i));
    MESHLOD_CHECK(level != nullptr);
    if (level)
    {
      MESHLOD_CHECK_EQ(level->GetPoints()->GetDataType(), VTK_DOUBLE);
    }
  }
  auto* level1 = vtkPolyData::SafeDownCast(h->GetBlock(1));
  const vtkIdType fractional = level1 ? FractionalCoordinates(level1) : 0;
  std::cout << name << ": " << fractional << " fractional coordinates on level 1\n";
  MESHLOD_CHECK_GT(fractional, 0);
  vtkNew<vtkLODGeomorph> morph;
  morph->SetInputData(h);
  morph->SetLevelOfDetail(0.5);
  morph->Update();
  MESHLOD_CHECK_EQ(morph->GetOutput()->GetPoints()->GetDataType(), VTK_DOUBLE);
  MESHLOD_CHECK_GT(FractionalCoordinates(morph->GetOutput()), 0);
}
} // namespace

int TestMeshLODFilterInputs(int, char*[])
{
  TestComposite<vtkTriangleCollapseDecimation>("vtkTriangleCollapseDecimation");
  TestComposite<vtkVertexClusterOctree>("vtkVertexClusterOctree");
  TestIntegerPoints<vtkTriangleCollapseDecimation>("vtkTriangleCollapseDecimation");
  TestIntegerPoints<vtkVertexClusterOctree>("vtkVertexClusterOctree");
  return testing::Result();
}
