// What both hierarchy filters make of inputs a pipeline can hand them besides a plain float or
// double surface: composite data (an error that says what to do, not a hierarchy nested in a
// hierarchy, which the pipeline's block-by-block execution made) and integer points (levels in
// double, not collapse points and geomorph frames truncated to integers); the point type
// OutputPointsPrecision asks for; and the cell global ids of quads, which their triangles share.
#include "vtkLODGeomorph.h"
#include "vtkTriangleCollapseDecimation.h"
#include "vtkVertexClusterOctree.h"

#include "MeshLODTestCheck.h"
#include "MeshLODTestMeshes.h"

#include "vtkAlgorithm.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkIdTypeArray.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkTestErrorObserver.h"

#include <algorithm>
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
// OutputPointsPrecision: every level (and a geomorph frame) in the type asked for, whatever the
// input's, the same triangle counts, and points within float rounding of the default's.
template <typename Filter>
void TestOutputPointsPrecision(const char* name)
{
  vtkSmartPointer<vtkPolyData> sphere = testing::MakeIcosphere(4);
  vtkNew<vtkPolyData> floatSphere, doubleSphere;
  for (vtkPolyData* copy : { floatSphere.Get(), doubleSphere.Get() })
  {
    vtkNew<vtkPoints> points;
    points->SetDataType(copy == floatSphere.Get() ? VTK_FLOAT : VTK_DOUBLE);
    for (vtkIdType p = 0; p < sphere->GetNumberOfPoints(); ++p)
    {
      points->InsertNextPoint(sphere->GetPoint(p));
    }
    copy->SetPoints(points);
    copy->SetPolys(sphere->GetPolys());
  }
  for (vtkPolyData* input : { floatSphere.Get(), doubleSphere.Get() })
  {
    vtkNew<Filter> reference;
    reference->SetInputData(input);
    reference->Update();
    vtkMultiBlockDataSet* expected = reference->GetHierarchy();
    for (const int precision : { vtkAlgorithm::SINGLE_PRECISION, vtkAlgorithm::DOUBLE_PRECISION,
           vtkAlgorithm::DEFAULT_PRECISION })
    {
      vtkNew<Filter> filter;
      filter->SetInputData(input);
      filter->SetOutputPointsPrecision(precision);
      filter->Update();
      vtkMultiBlockDataSet* h = filter->GetHierarchy();
      const int type = precision == vtkAlgorithm::SINGLE_PRECISION ? VTK_FLOAT
        : precision == vtkAlgorithm::DOUBLE_PRECISION            ? VTK_DOUBLE
                                                                 : input->GetPoints()->GetDataType();
      MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), expected->GetNumberOfBlocks());
      double largest = 0.0;
      for (unsigned int i = 0; i < h->GetNumberOfBlocks() && i < expected->GetNumberOfBlocks(); ++i)
      {
        auto* level = vtkPolyData::SafeDownCast(h->GetBlock(i));
        auto* other = vtkPolyData::SafeDownCast(expected->GetBlock(i));
        MESHLOD_REQUIRE(level && other);
        MESHLOD_CHECK_EQ(level->GetPoints()->GetDataType(), type);
        MESHLOD_CHECK_EQ(level->GetNumberOfPolys(), other->GetNumberOfPolys());
        if (level->GetNumberOfPoints() != other->GetNumberOfPoints())
        {
          MESHLOD_CHECK_EQ(level->GetNumberOfPoints(), other->GetNumberOfPoints());
          continue;
        }
        for (vtkIdType p = 0; p < level->GetNumberOfPoints(); ++p)
        {
          double x[3], y[3];
          level->GetPoint(p, x);
          other->GetPoint(p, y);
          for (int k = 0; k < 3; ++k)
          {
            largest = std::max(largest, std::abs(x[k] - y[k]));
          }
        }
      }
      // (A sphere of radius 1: float rounding is below 1e-7, and the collapses, which run on
      // the validated input in double either way, are the same.)
      MESHLOD_CHECK_LE(largest, 1e-6);
      vtkNew<vtkLODGeomorph> morph;
      morph->SetInputData(h);
      morph->SetLevelOfDetail(0.5);
      morph->Update();
      MESHLOD_CHECK_EQ(morph->GetOutput()->GetPoints()->GetDataType(), type);
    }
  }
  vtkNew<Filter> filter;
  filter->SetOutputPointsPrecision(7);
  MESHLOD_CHECK_EQ(filter->GetOutputPointsPrecision(), vtkAlgorithm::DEFAULT_PRECISION);
  std::cout << name << ": OutputPointsPrecision\n";
}
// Quads with cell GlobalIds: the two triangles of a quad share its id, so every level keeps the
// ids as a plain array of that name, each value one of the input's, and not as the attribute
// (which promises one cell per id).
template <typename Filter>
void TestPolygonCellIds(const char* name)
{
  vtkSmartPointer<vtkPolyData> grid = testing::MakeQuadGrid(20, 20);
  vtkNew<vtkIdTypeArray> ids;
  ids->SetName("QuadIds");
  for (vtkIdType q = 0; q < grid->GetNumberOfCells(); ++q)
  {
    ids->InsertNextValue(1001 + q);
  }
  grid->GetCellData()->SetGlobalIds(ids);
  vtkNew<Filter> filter;
  filter->SetInputData(grid);
  filter->Update();
  vtkMultiBlockDataSet* h = filter->GetHierarchy();
  MESHLOD_CHECK_GT(h->GetNumberOfBlocks(), 1u);
  for (unsigned int i = 0; i < h->GetNumberOfBlocks(); ++i)
  {
    auto* level = vtkPolyData::SafeDownCast(h->GetBlock(i));
    MESHLOD_REQUIRE(level != nullptr);
    vtkDataArray* kept = level->GetCellData()->GetArray("QuadIds");
    MESHLOD_CHECK(kept != nullptr && level->GetCellData()->GetGlobalIds() == nullptr);
    vtkIdType foreign = 0;
    for (vtkIdType c = 0; kept && c < kept->GetNumberOfTuples(); ++c)
    {
      const double value = kept->GetTuple1(c);
      foreign += value < 1001 || value > 1400 ? 1 : 0;
    }
    MESHLOD_CHECK_EQ(foreign, 0);
  }
  std::cout << name << ": quads' cell ids on " << h->GetNumberOfBlocks() << " levels\n";
}
} // namespace

int TestMeshLODFilterInputs(int, char*[])
{
  TestComposite<vtkTriangleCollapseDecimation>("vtkTriangleCollapseDecimation");
  TestComposite<vtkVertexClusterOctree>("vtkVertexClusterOctree");
  TestIntegerPoints<vtkTriangleCollapseDecimation>("vtkTriangleCollapseDecimation");
  TestIntegerPoints<vtkVertexClusterOctree>("vtkVertexClusterOctree");
  TestOutputPointsPrecision<vtkTriangleCollapseDecimation>("vtkTriangleCollapseDecimation");
  TestOutputPointsPrecision<vtkVertexClusterOctree>("vtkVertexClusterOctree");
  TestPolygonCellIds<vtkTriangleCollapseDecimation>("vtkTriangleCollapseDecimation");
  TestPolygonCellIds<vtkVertexClusterOctree>("vtkVertexClusterOctree");
  return testing::Result();
}
