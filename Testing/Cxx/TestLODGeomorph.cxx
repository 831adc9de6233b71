// vtkLODGeomorph with morph data: the partial collapse M_i(t) between the levels of a hierarchy
// built by independent triangle collapses on an icosphere, its point and cell data, dropped
// degenerate triangles, errors, and the same output for every SMP backend.
#include "vtkLODGeomorph.h"

#include "MeshLODHierarchyChecks.h"
#include "MeshLODHierarchy.h"
#include "MeshLODTestCheck.h"
#include "MeshLODTestHierarchies.h"
#include "MeshLODTestMeshes.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkMath.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkTestErrorObserver.h"

#include <cmath>
#include <functional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace
{
using namespace meshlod;
using testing::Level;
using testing::SameValues;

// The mesh with float or double points and point data: Height (double, = z), Label (int,
// 10 * id), Normals (float, the attribute), cell data CellLabel (int, 100 + id) and field data
// Scan (int, 7).
vtkSmartPointer<vtkPolyData> Decorate(vtkPolyData* mesh, int pointType)
{
  auto out = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->SetDataType(pointType);
  points->DeepCopy(mesh->GetPoints());
  out->SetPoints(points);
  out->SetPolys(mesh->GetPolys());
  vtkNew<vtkDoubleArray> height;
  height->SetName("Height");
  vtkNew<vtkIntArray> label;
  label->SetName("Label");
  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    double x[3];
    mesh->GetPoint(p, x);
    height->InsertNextValue(x[2]);
    label->InsertNextValue(static_cast<int>(10 * p));
    vtkMath::Normalize(x);
    normals->InsertNextTuple(x);
  }
  out->GetPointData()->AddArray(height);
  out->GetPointData()->AddArray(label);
  out->GetPointData()->SetNormals(normals);
  vtkNew<vtkIntArray> cellLabel;
  cellLabel->SetName("CellLabel");
  for (vtkIdType c = 0; c < mesh->GetNumberOfCells(); ++c)
  {
    cellLabel->InsertNextValue(static_cast<int>(100 + c));
  }
  out->GetCellData()->AddArray(cellLabel);
  vtkNew<vtkIntArray> scan;
  scan->SetName("Scan");
  scan->InsertNextValue(7);
  out->GetFieldData()->AddArray(scan);
  return out;
}

// The output's field data: LevelOfDetail, and the input's arrays as the levels share them, not
// the per-level ones of the layout (level index, triangle count and errors describe a level).
void CheckFieldData(vtkPolyData* out, vtkPolyData* level)
{
  vtkFieldData* fd = out->GetFieldData();
  MESHLOD_CHECK(fd->GetArray("Scan") != nullptr &&
    fd->GetArray("Scan") == level->GetFieldData()->GetArray("Scan"));
  MESHLOD_CHECK(fd->GetArray("LevelOfDetail") != nullptr);
  for (const char* own : { names::LevelIndex, names::NumberOfTriangles, names::EstimatedError })
  {
    MESHLOD_CHECK(fd->GetAbstractArray(own) == nullptr);
  }
}

vtkPolyData* Run(vtkLODGeomorph* filter, double lod)
{
  filter->SetLevelOfDetail(lod);
  filter->Update();
  return filter->GetOutput();
}

void TestHierarchy(vtkMultiBlockDataSet* h)
{
  MESHLOD_CHECK(CheckHierarchyLayout(h, true).empty());
  MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 4u);
  for (unsigned int i = 1; i < h->GetNumberOfBlocks(); ++i)
  {
    // Each collapse removes 4 triangles: counts fall by multiples of 4.
    const vtkIdType before = Level(h, i - 1)->GetNumberOfPolys();
    const vtkIdType after = Level(h, i)->GetNumberOfPolys();
    MESHLOD_CHECK_LT(after, before);
    MESHLOD_CHECK_EQ((before - after) % 4, 0);
  }
}

// L = 1: the output is level 1 itself (shared points, cells and arrays, no morph arrays).
void TestWholeLevel(vtkLODGeomorph* filter, vtkMultiBlockDataSet* h)
{
  vtkPolyData* out = Run(filter, 1.0);
  vtkPolyData* level = Level(h, 1);
  MESHLOD_CHECK(out->GetPoints() == level->GetPoints());
  MESHLOD_CHECK(out->GetPolys() == level->GetPolys());
  MESHLOD_CHECK(
    SameValues(out->GetPointData()->GetArray("Height"), level->GetPointData()->GetArray("Height")));
  MESHLOD_CHECK(out->GetPointData()->GetNormals() == level->GetPointData()->GetNormals());
  MESHLOD_CHECK(out->GetPointData()->GetArray(names::MorphTarget) == nullptr);
  MESHLOD_CHECK(out->GetPointData()->GetArray(names::MorphTargetId) == nullptr);
  MESHLOD_CHECK(out->GetPointData()->GetArray(names::CollapseRank) == nullptr);
  MESHLOD_CHECK(
    out->GetCellData()->GetArray("CellLabel") == level->GetCellData()->GetArray("CellLabel"));
  MESHLOD_CHECK_EQ(filter->GetActualLevelOfDetail(), 1.0);
  MESHLOD_CHECK_EQ(out->GetFieldData()->GetArray("LevelOfDetail")->GetTuple1(0), 1.0);
  CheckFieldData(out, level);
  MESHLOD_CHECK_EQ(filter->GetNumberOfLevels(), 4);
  MESHLOD_CHECK_EQ(filter->GetActualCorrespondence(), vtkLODGeomorph::MORPH_ARRAYS);
}

// Within level 1: fixed connectivity (level 1's cell array, shared), points on the segments
// p -> MorphTarget(p), arrays blended or switched.
void TestWithinLevel(vtkLODGeomorph* filter, vtkMultiBlockDataSet* h)
{
  vtkPolyData* level = Level(h, 1);
  vtkPolyData* next = Level(h, 2);
  vtkDataArray* target = level->GetPointData()->GetArray(names::MorphTarget);
  vtkDataArray* targetId = level->GetPointData()->GetArray(names::MorphTargetId);
  for (const double t : { 0.25, 0.5, 0.75 })
  {
    vtkPolyData* out = Run(filter, 1.0 + t);
    MESHLOD_CHECK(out->GetPolys() == level->GetPolys());
    MESHLOD_CHECK_EQ(out->GetNumberOfPoints(), level->GetNumberOfPoints());
    MESHLOD_CHECK_EQ(filter->GetActualNumberOfTriangles(), level->GetNumberOfPolys());
    MESHLOD_CHECK(
      out->GetCellData()->GetArray("CellLabel") == level->GetCellData()->GetArray("CellLabel"));
    double worst = 0.0;
    int wrongHeight = 0, wrongLabel = 0, notUnit = 0;
    for (vtkIdType p = 0; p < out->GetNumberOfPoints(); ++p)
    {
      double x[3], a[3], b[3];
      out->GetPoint(p, x);
      level->GetPoint(p, a);
      target->GetTuple(p, b);
      for (int c = 0; c < 3; ++c)
      {
        worst = std::max(worst, std::abs(x[c] - ((1 - t) * a[c] + t * b[c])));
      }
      const vtkIdType q = static_cast<vtkIdType>(targetId->GetTuple1(p));
      const double h0 = level->GetPointData()->GetArray("Height")->GetTuple1(p);
      const double h1 = next->GetPointData()->GetArray("Height")->GetTuple1(q);
      wrongHeight += out->GetPointData()->GetArray("Height")->GetTuple1(p) != (1 - t) * h0 + t * h1;
      const double label = t >= 0.5 ? next->GetPointData()->GetArray("Label")->GetTuple1(q)
                                    : level->GetPointData()->GetArray("Label")->GetTuple1(p);
      wrongLabel += out->GetPointData()->GetArray("Label")->GetTuple1(p) != label;
      double n[3];
      out->GetPointData()->GetNormals()->GetTuple(p, n);
      notUnit += std::abs(vtkMath::Norm(n) - 1.0) > 1e-6;
    }
    MESHLOD_CHECK_LE(worst, 1e-15);
    MESHLOD_CHECK_EQ(wrongHeight, 0);
    MESHLOD_CHECK_EQ(wrongLabel, 0);
    MESHLOD_CHECK_EQ(notUnit, 0);
    MESHLOD_CHECK(out->GetPointData()->GetNormals() != nullptr);
    MESHLOD_CHECK(out->GetPointData()->GetArray(names::MorphTarget) == nullptr);
    CheckFieldData(out, level);
  }
  // t = 0.5 exactly: one point checked by hand against both levels.
  vtkPolyData* out = Run(filter, 1.5);
  const vtkIdType q = static_cast<vtkIdType>(targetId->GetTuple1(0));
  MESHLOD_CHECK_EQ(out->GetPointData()->GetArray("Height")->GetTuple1(0),
    0.5 * level->GetPointData()->GetArray("Height")->GetTuple1(0) +
      0.5 * next->GetPointData()->GetArray("Height")->GetTuple1(q));
}

// As t -> 1 every point tends to its point in the next level.
void TestLimit(vtkLODGeomorph* filter, vtkMultiBlockDataSet* h)
{
  for (int i = 0; i + 1 < 4; ++i)
  {
    vtkPolyData* level = Level(h, i);
    vtkPolyData* next = Level(h, i + 1);
    vtkDataArray* targetId = level->GetPointData()->GetArray(names::MorphTargetId);
    vtkPolyData* out = Run(filter, i + (1.0 - std::ldexp(1.0, -45)));
    MESHLOD_CHECK(out->GetPolys() == level->GetPolys());
    double worst = 0.0;
    for (vtkIdType p = 0; p < out->GetNumberOfPoints(); ++p)
    {
      double x[3], y[3];
      out->GetPoint(p, x);
      next->GetPoint(static_cast<vtkIdType>(targetId->GetTuple1(p)), y);
      worst = std::max(worst, std::sqrt(vtkMath::Distance2BetweenPoints(x, y)));
    }
    MESHLOD_CHECK_LE(worst, 1e-12);
  }
}

// Float points near t = 1 round onto the collapse points: the collapsing triangles and their
// edge neighbours degenerate and DropDegenerateTriangles removes exactly them.
void TestDropDegenerate(vtkMultiBlockDataSet* h)
{
  vtkNew<vtkLODGeomorph> filter;
  filter->SetInputData(h);
  filter->DropDegenerateTrianglesOn();
  vtkPolyData* out = Run(filter, 0.5);
  MESHLOD_CHECK(out->GetPolys() == Level(h, 0)->GetPolys());
  out = Run(filter, 1.0 - std::ldexp(1.0, -45));
  MESHLOD_CHECK_EQ(out->GetNumberOfPolys(), Level(h, 1)->GetNumberOfPolys());
  MESHLOD_CHECK_EQ(out->GetCellData()->GetArray("CellLabel")->GetNumberOfTuples(),
    Level(h, 1)->GetNumberOfPolys());
  filter->DropDegenerateTrianglesOff();
  out = Run(filter, 1.0 - std::ldexp(1.0, -45));
  MESHLOD_CHECK_EQ(out->GetNumberOfPolys(), Level(h, 0)->GetNumberOfPolys());
}

// Beyond the coarsest level: clamped, with a warning.
void TestClamp(vtkMultiBlockDataSet* h)
{
  vtkNew<vtkLODGeomorph> filter;
  vtkNew<vtkTest::ErrorObserver> observer;
  filter->AddObserver(vtkCommand::WarningEvent, observer);
  filter->SetInputData(h);
  vtkPolyData* out = Run(filter, 7.5);
  MESHLOD_CHECK(observer->GetWarning());
  MESHLOD_CHECK(out->GetPoints() == Level(h, 3)->GetPoints());
  MESHLOD_CHECK_EQ(filter->GetActualLevelOfDetail(), 3.0);
  filter->SetLevelOfDetail(-2.0);
  MESHLOD_CHECK_EQ(filter->GetLevelOfDetail(), 0.0);
  filter->SetTimeScale(-1.0);
  MESHLOD_CHECK_GT(filter->GetTimeScale(), 0.0);
  filter->SetMergeTolerance(2.0);
  MESHLOD_CHECK_EQ(filter->GetMergeTolerance(), 1.0);
  filter->SetCollapseFraction(-0.5);
  MESHLOD_CHECK_EQ(filter->GetCollapseFraction(), 0.0);

  // Every setting printed.
  std::ostringstream printed;
  filter->Print(printed);
  for (const char* setting : { "LevelOfDetail", "UsePipelineTime", "TimeScale",
         "TargetNumberOfTriangles", "CollapseFraction", "DropDegenerateTriangles",
         "Correspondence", "MergeTolerance" })
  {
    MESHLOD_CHECK(printed.str().find(setting) != std::string::npos);
  }
}

int ExpectError(vtkDataObject* input, const std::string& expected,
  const std::function<void(vtkLODGeomorph*)>& configure = nullptr)
{
  vtkNew<vtkLODGeomorph> filter;
  vtkNew<vtkTest::ErrorObserver> observer;
  filter->AddObserver(vtkCommand::ErrorEvent, observer);
  filter->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, observer);
  filter->SetInputData(input);
  filter->SetLevelOfDetail(0.5);
  if (configure)
  {
    configure(filter);
  }
  filter->Update();
  MESHLOD_CHECK(observer->GetError());
  if (observer->GetErrorMessage().find(expected) == std::string::npos)
  {
    std::cerr << "unexpected error message: " << observer->GetErrorMessage() << "\n";
    ++testing::FailureCount();
  }
  MESHLOD_CHECK(filter->GetOutput() == nullptr || filter->GetOutput()->GetNumberOfPoints() == 0);
  MESHLOD_CHECK_EQ(filter->GetActualLevelOfDetail(), -1.0);
  MESHLOD_CHECK_EQ(filter->GetActualNumberOfTriangles(), 0);
  return 0;
}

void TestErrors(vtkMultiBlockDataSet* h)
{
  vtkNew<vtkMultiBlockDataSet> empty;
  ExpectError(empty, "has no levels");

  vtkNew<vtkMultiBlockDataSet> mixed;
  mixed->SetNumberOfBlocks(2);
  mixed->SetBlock(0, Level(h, 0));
  vtkNew<vtkImageData> image;
  mixed->SetBlock(1, image);
  ExpectError(mixed, "block 1 is not a vtkPolyData");

  // A polydata instead of a hierarchy: refused by the pipeline.
  ExpectError(Level(h, 0), "vtkMultiBlockDataSet");

  // Morph arrays pointing outside the next level.
  vtkNew<vtkMultiBlockDataSet> broken;
  broken->SetNumberOfBlocks(2);
  vtkNew<vtkPolyData> level0;
  level0->DeepCopy(Level(h, 0));
  level0->GetPointData()->GetArray(names::MorphTargetId)->SetTuple1(3, 1e6);
  broken->SetBlock(0, level0);
  broken->SetBlock(1, Level(h, 1));
  ExpectError(broken, "outside");
  // ... or not where the point they name is, not integers, or ranks below -1 (each was
  // blended or scheduled silently).
  const std::vector<std::pair<std::function<void(vtkPointData*)>, std::string>> edits = {
    { [](vtkPointData* pd) { pd->GetArray(names::MorphTarget)->SetTuple3(3, 5.0, 5.0, 5.0); },
      "level 0's MorphTarget of point 3 is not where its MorphTargetId point of level 1 is" },
    { [](vtkPointData* pd) {
       vtkNew<vtkDoubleArray> ids;
       ids->DeepCopy(pd->GetArray(names::MorphTargetId));
       ids->SetTuple1(3, ids->GetTuple1(3) + 0.5);
       pd->AddArray(ids);
     },
      "or not integers" },
    { [](vtkPointData* pd) { pd->GetArray(names::CollapseRank)->SetTuple1(3, -7); },
      "level 0 has CollapseRank values that are neither -1 nor a rank" },
  };
  for (const auto& edit : edits)
  {
    level0->DeepCopy(Level(h, 0));
    edit.first(level0->GetPointData());
    ExpectError(broken, edit.second);
  }

  // Incomplete morph arrays (MorphTarget missing on level 1 of 3).
  vtkNew<vtkMultiBlockDataSet> incomplete;
  incomplete->SetNumberOfBlocks(3);
  vtkNew<vtkPolyData> level1;
  level1->DeepCopy(Level(h, 1));
  level1->GetPointData()->RemoveArray(names::MorphTarget);
  incomplete->SetBlock(0, Level(h, 0));
  incomplete->SetBlock(1, level1);
  incomplete->SetBlock(2, Level(h, 2));
  ExpectError(incomplete, "lacks complete");

  // A cell of a hand-edited level that refers to a point it does not have: refused before any
  // mode reads the cells (the exact count, the nearest-vertex correspondence and the dropping
  // of degenerate triangles crashed on it; a plain blend copied the bad id to its output).
  vtkNew<vtkPolyData> badIds;
  badIds->DeepCopy(Level(h, 0));
  vtkNew<vtkCellArray> cells;
  cells->DeepCopy(badIds->GetPolys());
  cells->GetConnectivityArray()->SetTuple1(7, 1e6);
  badIds->SetPolys(cells);
  vtkNew<vtkMultiBlockDataSet> outside;
  outside->SetNumberOfBlocks(2);
  outside->SetBlock(0, badIds);
  outside->SetBlock(1, Level(h, 1));
  const std::function<void(vtkLODGeomorph*)> modes[] = { nullptr,
    [h](vtkLODGeomorph* f) { f->SetTargetNumberOfTriangles(Level(h, 0)->GetNumberOfPolys() / 2); },
    [](vtkLODGeomorph* f) { f->SetCorrespondenceToNearestVertices(); },
    [](vtkLODGeomorph* f) { f->DropDegenerateTrianglesOn(); } };
  for (const auto& mode : modes)
  {
    ExpectError(outside, "level 0 has a cell that refers to a point id outside [0, ", mode);
  }
  // Triangles but no points at all.
  vtkNew<vtkPolyData> pointless;
  pointless->DeepCopy(Level(h, 0));
  pointless->SetPoints(nullptr);
  outside->SetBlock(0, pointless);
  ExpectError(outside, "outside [0, 0)",
    [](vtkLODGeomorph* f) { f->SetCorrespondenceToNearestVertices(); });

  // NaN positions or morph targets: an error naming the level and point (they went through
  // every blend into the output).
  {
    vtkNew<vtkPolyData> nanPoint, nanTarget;
    nanPoint->DeepCopy(Level(h, 1));
    nanPoint->GetPoints()->SetPoint(4, std::nan(""), 0.0, 0.0);
    nanTarget->DeepCopy(Level(h, 0));
    nanTarget->GetPointData()->GetArray(names::MorphTarget)->SetComponent(9, 2, INFINITY);
    vtkNew<vtkMultiBlockDataSet> nan;
    nan->SetNumberOfBlocks(2);
    nan->SetBlock(0, Level(h, 0));
    nan->SetBlock(1, nanPoint);
    ExpectError(nan, "level 1's point 4 has a NaN or infinite coordinate");
    nan->SetBlock(0, nanTarget);
    nan->SetBlock(1, Level(h, 1));
    ExpectError(nan, "level 0's MorphTarget of point 9 is NaN or infinite");
  }

  // A point array shorter than its level: left out with a warning (blending it read past its
  // end, garbage in the output).
  {
    vtkNew<vtkPolyData> fine, coarse;
    fine->ShallowCopy(Level(h, 0));
    coarse->ShallowCopy(Level(h, 1));
    for (vtkPolyData* level : { fine.Get(), coarse.Get() })
    {
      vtkNew<vtkFloatArray> shortArray;
      shortArray->SetName("Short");
      shortArray->SetNumberOfTuples(level == fine ? 3 : 2);
      shortArray->Fill(1.0);
      level->GetPointData()->AddArray(shortArray);
    }
    vtkNew<vtkMultiBlockDataSet> mismatched;
    mismatched->SetNumberOfBlocks(2);
    mismatched->SetBlock(0, fine);
    mismatched->SetBlock(1, coarse);
    for (const auto& mode : { modes[0], modes[1] })
    {
      vtkNew<vtkLODGeomorph> filter;
      vtkNew<vtkTest::ErrorObserver> observer;
      filter->AddObserver(vtkCommand::ErrorEvent, observer);
      filter->AddObserver(vtkCommand::WarningEvent, observer);
      filter->SetInputData(mismatched);
      filter->SetLevelOfDetail(0.5);
      if (mode)
      {
        mode(filter);
      }
      filter->Update();
      MESHLOD_CHECK(!observer->GetError());
      MESHLOD_CHECK(observer->GetWarningMessage().find("\"Short\"") != std::string::npos);
      vtkPolyData* out = filter->GetOutput();
      MESHLOD_CHECK_GT(out->GetNumberOfPolys(), 0);
      MESHLOD_CHECK(out->GetPointData()->GetAbstractArray("Short") == nullptr);
      // The input keeps its arrays.
      MESHLOD_CHECK(fine->GetPointData()->GetAbstractArray("Short") != nullptr);
    }
  }

  // An empty level: an empty output, no error.
  vtkNew<vtkMultiBlockDataSet> hollow;
  hollow->SetNumberOfBlocks(1);
  vtkNew<vtkPolyData> nothing;
  hollow->SetBlock(0, nothing);
  vtkNew<vtkLODGeomorph> filter;
  vtkNew<vtkTest::ErrorObserver> observer;
  filter->AddObserver(vtkCommand::ErrorEvent, observer);
  filter->SetInputData(hollow);
  filter->Update();
  MESHLOD_CHECK(!observer->GetError());
  MESHLOD_CHECK_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);
}

// The same points, arrays and cells for the sequential and the default SMP backend.
void TestBackends(vtkMultiBlockDataSet* h)
{
  const std::string initial = vtkSMPTools::GetBackend();
  const auto runs = testing::RunWithBothBackends([&] {
    vtkNew<vtkLODGeomorph> filter;
    filter->SetInputData(h);
    return vtkSmartPointer<vtkPolyData>(Run(filter, 0.37));
  });
  vtkPolyData* sequential = runs.first;
  vtkPolyData* parallel = runs.second;
  MESHLOD_CHECK(SameValues(sequential->GetPoints()->GetData(), parallel->GetPoints()->GetData()));
  MESHLOD_CHECK(SameValues(
    sequential->GetPointData()->GetArray("Height"), parallel->GetPointData()->GetArray("Height")));
  MESHLOD_CHECK(
    SameValues(sequential->GetPointData()->GetNormals(), parallel->GetPointData()->GetNormals()));
  MESHLOD_CHECK_EQ(std::string(vtkSMPTools::GetBackend()), initial);
}
} // namespace

int TestLODGeomorph(int, char*[])
{
  testing::CollapseHierarchyOptions options;
  options.MaximumLevels = 4;
  options.MaximumFraction = 0.5;
  vtkSmartPointer<vtkPolyData> sphere = Decorate(testing::MakeIcosphere(3), VTK_DOUBLE);
  vtkSmartPointer<vtkMultiBlockDataSet> h = testing::MakeCollapseHierarchy(sphere, options);
  TestHierarchy(h);

  vtkNew<vtkLODGeomorph> filter;
  filter->SetInputData(h);
  TestWholeLevel(filter, h);
  TestWithinLevel(filter, h);
  TestLimit(filter, h);

  vtkSmartPointer<vtkPolyData> floatSphere = Decorate(testing::MakeIcosphere(3), VTK_FLOAT);
  TestDropDegenerate(testing::MakeCollapseHierarchy(floatSphere, options));
  TestClamp(h);
  TestErrors(h);
  TestBackends(h);
  return testing::Result();
}
