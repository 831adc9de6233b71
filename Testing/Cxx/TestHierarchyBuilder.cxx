// The shared hierarchy layout (MeshLODHierarchy.h) on a hand-made two-level hierarchy.
#include "MeshLODHierarchy.h"
#include "MeshLODInputMesh.h"
#include "MeshLODTestCheck.h"
#include "MeshLODTestMeshes.h"

#include "vtkAlgorithm.h"
#include "vtkCellData.h"
#include "vtkCompositeDataSet.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkIntArray.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkTriangleFilter.h"

#include <cmath>

int TestHierarchyBuilder(int, char*[])
{
  using namespace meshlod;
  // Level 0: the 2x1 grid (points 0 1 2 / 3 4 5, triangles (0,1,4) (0,4,3) (1,2,5) (1,5,4)),
  // with a float "Height" = point id, an int "Label" = 10 * point id, and a cell array.
  vtkSmartPointer<vtkPolyData> grid = testing::MakeGrid(2, 1);
  vtkNew<vtkDoubleArray> height;
  height->SetName("Height");
  vtkNew<vtkIntArray> label;
  label->SetName("Label");
  for (int p = 0; p < 6; ++p)
  {
    height->InsertNextValue(p);
    label->InsertNextValue(10 * p);
  }
  grid->GetPointData()->AddArray(height);
  grid->GetPointData()->AddArray(label);
  vtkNew<vtkIntArray> cellLabel;
  cellLabel->SetName("CellLabel");
  for (int c = 0; c < 4; ++c)
  {
    cellLabel->InsertNextValue(100 + c);
  }
  grid->GetCellData()->AddArray(cellLabel);

  vtkNew<vtkTriangleFilter> caller;
  InputMesh input;
  MESHLOD_CHECK(ReadInputMesh(grid, caller, input) == InputStatus::Valid);
  HierarchyBuilder builder;
  builder.SetLevelZero(input, vtkAlgorithm::DEFAULT_PRECISION);

  // Level 1: points 1 and 4 merge into a new point at (1, 0.5); triangles (0,4,3) and (1,2,5)
  // survive. New points: 0 <- 0, 1 <- {1, 4}, 2 <- 2, 3 <- 3, 4 <- 5.
  LevelData level;
  level.Mesh.Points = { 0, 0, 0, 1, 0.5, 0, 2, 0, 0, 0, 1, 0, 2, 1, 0 };
  level.Mesh.Triangles = { 0, 1, 3, 1, 2, 4 };
  level.LevelZeroTriangle = { 1, 2 };
  level.Sources.Clear();
  const Id single[] = { 0, 2, 3, 5 };
  const float one = 1.0f;
  level.Sources.Add(&single[0], &one, 1);
  const Id pair[2] = { 4, 1 };
  const float halves[2] = { 0.5f, 0.5f };
  level.Sources.Add(pair, halves, 2);
  level.Sources.Add(&single[1], &one, 1);
  level.Sources.Add(&single[2], &one, 1);
  level.Sources.Add(&single[3], &one, 1);
  level.Target = { 0, 1, 2, 3, 1, 4 };
  level.Rank = { -1, 0, -1, -1, 0, -1 };
  level.EstimatedError = 0.25;
  builder.AppendLevel(std::move(level));
  builder.MeasureLevelErrors();

  vtkNew<vtkMultiBlockDataSet> hierarchy;
  builder.Finish(hierarchy);
  MESHLOD_CHECK_EQ(hierarchy->GetNumberOfBlocks(), 2u);
  MESHLOD_CHECK(CheckHierarchyLayout(hierarchy, true).empty());
  MESHLOD_CHECK_EQ(std::string(hierarchy->GetMetaData(1u)->Get(vtkCompositeDataSet::NAME())),
    std::string("Level 1"));

  auto* l0 = vtkPolyData::SafeDownCast(hierarchy->GetBlock(0));
  auto* l1 = vtkPolyData::SafeDownCast(hierarchy->GetBlock(1));
  // Level 0 shares the clean input's points, but the input itself gains no arrays.
  MESHLOD_CHECK(l0->GetPoints() == grid->GetPoints());
  MESHLOD_CHECK(grid->GetPointData()->GetArray(names::MorphTargetId) == nullptr);
  vtkDataArray* targetId = l0->GetPointData()->GetArray(names::MorphTargetId);
  vtkDataArray* target = l0->GetPointData()->GetArray(names::MorphTarget);
  MESHLOD_CHECK_EQ(targetId->GetTuple1(4), 1.0);
  MESHLOD_CHECK_EQ(target->GetComponent(4, 1), 0.5);
  MESHLOD_CHECK_EQ(l0->GetPointData()->GetArray(names::CollapseRank)->GetTuple1(2), -1.0);

  // Interpolated and categorical point data, cell data of the surviving cells.
  MESHLOD_CHECK_EQ(l1->GetPointData()->GetArray("Height")->GetTuple1(1), 2.5);
  MESHLOD_CHECK_EQ(l1->GetPointData()->GetArray("Height")->GetTuple1(4), 5.0);
  MESHLOD_CHECK_EQ(l1->GetPointData()->GetArray("Label")->GetTuple1(1), 40.0); // first on ties
  MESHLOD_CHECK(l1->GetPointData()->GetArray(names::MorphTarget) == nullptr);
  MESHLOD_CHECK_EQ(l1->GetCellData()->GetArray("CellLabel")->GetTuple1(0), 101.0);
  MESHLOD_CHECK_EQ(l1->GetCellData()->GetArray("CellLabel")->GetTuple1(1), 102.0);

  // Field data.
  vtkFieldData* fd = l1->GetFieldData();
  MESHLOD_CHECK_EQ(fd->GetArray(names::LevelIndex)->GetTuple1(0), 1.0);
  MESHLOD_CHECK_EQ(fd->GetArray(names::NumberOfTriangles)->GetTuple1(0), 2.0);
  MESHLOD_CHECK_EQ(fd->GetArray(names::EstimatedError)->GetTuple1(0), 0.25);
  MESHLOD_CHECK_GT(fd->GetArray(names::MeasuredHausdorff)->GetTuple1(0), 0.4);
  MESHLOD_CHECK_EQ(l0->GetFieldData()->GetArray(names::MeasuredHausdorff)->GetTuple1(0), 0.0);

  // A broken correspondence is reported.
  l0->GetPointData()->GetArray(names::MorphTargetId)->SetTuple1(3, 7);
  MESHLOD_CHECK(!CheckHierarchyLayout(hierarchy, true).empty());
  return meshlod::testing::Result();
}
