// vtkLODGeomorph's exact triangle count: a sweep of counts on a closed icosphere hierarchy
// (exact counts, valid closed manifolds), the geomorph of the next collapse, the end of a
// transition equal to the next level, a hand-made cluster collapse on an open grid, clamping,
// an abort while the order is built.
#include "vtkLODGeomorph.h"

#include "Core/TriangleMesh.h"
#include "MeshLODHierarchyChecks.h"
#include "MeshLODHierarchy.h"
#include "MeshLODInputMesh.h"
#include "MeshLODTestCheck.h"
#include "MeshLODTestHierarchies.h"
#include "MeshLODTestMeshes.h"

#include "vtkAlgorithm.h"
#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkCommand.h"
#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkIntArray.h"
#include "vtkMath.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkTestErrorObserver.h"
#include "vtkTriangleFilter.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <vector>

namespace
{
using namespace meshlod;
using testing::Level;

vtkPolyData* Run(vtkLODGeomorph* filter, vtkIdType count, double fraction = 0.0)
{
  filter->SetTargetNumberOfTriangles(count);
  filter->SetCollapseFraction(fraction);
  filter->Update();
  return filter->GetOutput();
}

// Distinct point positions, sorted.
std::vector<std::array<double, 3>> Positions(vtkPolyData* poly)
{
  std::vector<std::array<double, 3>> positions(poly->GetNumberOfPoints());
  for (vtkIdType p = 0; p < poly->GetNumberOfPoints(); ++p)
  {
    poly->GetPoint(p, positions[p].data());
  }
  std::sort(positions.begin(), positions.end());
  positions.erase(std::unique(positions.begin(), positions.end()), positions.end());
  return positions;
}

// Closed, manifold, consistently oriented, genus 0, every point used, no degenerate or
// repeated triangle.
bool IsValidSphere(vtkPolyData* poly)
{
  const TriangleMesh mesh = testing::ToTriangleMesh(poly);
  TriangleTopology topology;
  topology.Build(mesh);
  const TriangleTopology::EdgeCounts edges = topology.CountEdges(mesh);
  bool ok = edges.Boundary == 0 && edges.NonManifold == 0 &&
    topology.IsConsistentlyOriented(mesh) && topology.EulerCharacteristic(mesh) == 2 &&
    topology.CountVertices(VertexKind::Unused) == 0 &&
    topology.CountVertices(VertexKind::NonManifold) == 0;
  std::set<std::array<Id, 3>> seen;
  for (Id t = 0; t < mesh.GetNumberOfTriangles() && ok; ++t)
  {
    const Id* tri = mesh.Triangle(t);
    double n[3];
    const double* a = mesh.Point(tri[0]);
    const double u[3] = { mesh.Point(tri[1])[0] - a[0], mesh.Point(tri[1])[1] - a[1],
      mesh.Point(tri[1])[2] - a[2] };
    const double v[3] = { mesh.Point(tri[2])[0] - a[0], mesh.Point(tri[2])[1] - a[1],
      mesh.Point(tri[2])[2] - a[2] };
    vtkMath::Cross(u, v, n);
    std::array<Id, 3> key = { tri[0], tri[1], tri[2] };
    std::sort(key.begin(), key.end());
    ok = vtkMath::Norm(n) > 1e-12 && seen.insert(key).second;
  }
  return ok;
}

// Every count between the coarsest and the finest level: closed manifolds lose two triangles
// per step, so even counts are exact and odd counts give the even count below.
void TestSweep(vtkMultiBlockDataSet* h)
{
  vtkNew<vtkLODGeomorph> filter;
  filter->SetInputData(h);
  const int n = static_cast<int>(h->GetNumberOfBlocks());
  const vtkIdType finest = Level(h, 0)->GetNumberOfPolys();
  const vtkIdType coarsest = Level(h, n - 1)->GetNumberOfPolys();
  int wrongCount = 0, invalid = 0, wrongCellData = 0, wrongPoints = 0;
  for (vtkIdType count = coarsest; count <= finest; ++count)
  {
    vtkPolyData* out = Run(filter, count);
    const vtkIdType expected = count - count % 2;
    wrongCount += out->GetNumberOfPolys() != expected;
    wrongCount += filter->GetActualNumberOfTriangles() != expected;
    invalid += !IsValidSphere(out);
    wrongCellData +=
      out->GetCellData()->GetArray("CellLabel")->GetNumberOfTuples() != out->GetNumberOfPolys();
    wrongPoints += out->GetNumberOfPoints() != expected / 2 + 2; // Euler, genus 0
  }
  MESHLOD_CHECK_EQ(wrongCount, 0);
  MESHLOD_CHECK_EQ(invalid, 0);
  MESHLOD_CHECK_EQ(wrongCellData, 0);
  MESHLOD_CHECK_EQ(wrongPoints, 0);

  // A level's own count gives that level itself.
  vtkPolyData* out = Run(filter, Level(h, 1)->GetNumberOfPolys());
  MESHLOD_CHECK(out->GetPoints() == Level(h, 1)->GetPoints());
  MESHLOD_CHECK_EQ(filter->GetActualLevelOfDetail(), 1.0);
}

// The next collapse moves with CollapseFraction; at 1 the points sit where the next count puts
// them; at the end of a transition, where the next level has them.
void TestFraction(vtkMultiBlockDataSet* h)
{
  vtkNew<vtkLODGeomorph> filter;
  filter->SetInputData(h);
  const vtkIdType count = Level(h, 0)->GetNumberOfPolys() - 10;

  vtkNew<vtkPolyData> still;
  still->DeepCopy(Run(filter, count, 0.0));
  vtkCellArray* cells = filter->GetOutput()->GetPolys();
  vtkPolyData* half = Run(filter, count, 0.5);
  MESHLOD_CHECK_EQ(half->GetNumberOfPolys(), count);
  MESHLOD_CHECK(half->GetPolys() == cells); // only the fraction changed: topology reused
  int moved = 0;
  for (vtkIdType p = 0; p < half->GetNumberOfPoints(); ++p)
  {
    double a[3], b[3];
    still->GetPoint(p, a);
    half->GetPoint(p, b);
    moved += vtkMath::Distance2BetweenPoints(a, b) > 0.0;
  }
  // The next collapse that removes triangles: one point (joining a settled one) or two.
  MESHLOD_CHECK_GE(moved, 1);
  MESHLOD_CHECK_LE(moved, 2);
  const std::vector<std::array<double, 3>> arrived = Positions(Run(filter, count, 1.0));
  MESHLOD_CHECK_EQ(filter->GetActualNumberOfTriangles(), count);
  MESHLOD_CHECK(arrived == Positions(Run(filter, count - 2, 0.0)));

  // At a level's own count the fraction moves that level's first collapse: from a level's
  // count with fraction 1 to the count below with 0 nothing jumps (level 0 and level 1).
  for (int i = 0; i < 2; ++i)
  {
    const vtkIdType own = Level(h, i)->GetNumberOfPolys();
    MESHLOD_CHECK(Positions(Run(filter, own, 0.0)) == Positions(Level(h, i)));
    const std::vector<std::array<double, 3>> full = Positions(Run(filter, own, 1.0));
    MESHLOD_CHECK_EQ(filter->GetActualNumberOfTriangles(), own);
    MESHLOD_CHECK_GT(filter->GetActualLevelOfDetail(), static_cast<double>(i));
    MESHLOD_CHECK(full != Positions(Level(h, i)));
    MESHLOD_CHECK(full == Positions(Run(filter, own - 2, 0.0)));
  }

  // The last two triangles of the transition 0 -> 1, fully moved: every point is at its
  // target, i.e. the positions are level 1's.
  const vtkIdType nextLevel = Level(h, 1)->GetNumberOfPolys();
  vtkPolyData* end = Run(filter, nextLevel + 2, 1.0);
  MESHLOD_CHECK_EQ(end->GetNumberOfPolys(), nextLevel + 2);
  MESHLOD_CHECK(Positions(end) == Positions(Level(h, 1)));
  // Still level 0's points and data: L below 1 (it read 1 when the fraction moved the last
  // step all the way, naming level 1's texture block for level 0's TCoords).
  MESHLOD_CHECK_LT(filter->GetActualLevelOfDetail(), 1.0);
  MESHLOD_CHECK_GT(filter->GetActualLevelOfDetail(), 0.99);

  // Point data: a settled point has the next level's values (Height = z of the collapse
  // point, interpolated by the hierarchy with float weights), a still one keeps its own.
  vtkPolyData* out = Run(filter, count, 0.0);
  vtkDataArray* height = out->GetPointData()->GetArray("Height");
  MESHLOD_CHECK(height != nullptr);
  int wrong = 0;
  for (vtkIdType p = 0; p < out->GetNumberOfPoints(); ++p)
  {
    double x[3];
    out->GetPoint(p, x);
    wrong += std::abs(height->GetTuple1(p) - x[2]) > 1e-6;
  }
  MESHLOD_CHECK_EQ(wrong, 0);
}

// The grid of TestGeomorphCore with the middle points 5, 6, 9, 10 clustered at (1.5, 1.5):
// an open mesh and a four-point collapse.
vtkSmartPointer<vtkMultiBlockDataSet> MakeGridHierarchy()
{
  vtkSmartPointer<vtkPolyData> grid = testing::MakeGrid(3, 3);
  vtkNew<vtkDoubleArray> height;
  height->SetName("Height");
  for (vtkIdType p = 0; p < 16; ++p)
  {
    height->InsertNextValue(static_cast<double>(p));
  }
  grid->GetPointData()->AddArray(height);
  vtkNew<vtkTriangleFilter> caller;
  InputMesh input;
  ReadInputMesh(grid, caller, input);
  HierarchyBuilder builder;
  builder.SetLevelZero(input, vtkAlgorithm::DEFAULT_PRECISION);

  LevelData level;
  level.Sources.Clear();
  level.Target.resize(16);
  level.Rank.assign(16, -1);
  const float one = 1.0f;
  const Id cluster[4] = { 5, 6, 9, 10 };
  const float quarter[4] = { 0.25f, 0.25f, 0.25f, 0.25f };
  for (Id p = 0; p < 16; ++p)
  {
    const bool inCluster = p == 5 || p == 6 || p == 9 || p == 10;
    if (inCluster && p != 5)
    {
      level.Target[p] = level.Target[5];
      level.Rank[p] = 0;
      continue;
    }
    level.Target[p] = level.Mesh.GetNumberOfPoints();
    if (inCluster)
    {
      level.Rank[p] = 0;
      level.Mesh.Points.insert(level.Mesh.Points.end(), { 1.5, 1.5, 0.0 });
      level.Sources.Add(cluster, quarter, 4);
    }
    else
    {
      level.Mesh.Points.insert(
        level.Mesh.Points.end(), input.Mesh.Point(p), input.Mesh.Point(p) + 3);
      level.Sources.Add(&p, &one, 1);
    }
  }
  for (Id t = 0; t < input.Mesh.GetNumberOfTriangles(); ++t)
  {
    const Id* tri = input.Mesh.Triangle(t);
    const Id a = level.Target[tri[0]], b = level.Target[tri[1]], c = level.Target[tri[2]];
    if (a != b && b != c && c != a)
    {
      level.Mesh.Triangles.insert(level.Mesh.Triangles.end(), { a, b, c });
      level.LevelZeroTriangle.push_back(t);
    }
  }
  builder.AppendLevel(std::move(level));
  auto hierarchy = vtkSmartPointer<vtkMultiBlockDataSet>::New();
  builder.Finish(hierarchy);
  return hierarchy;
}

void TestCluster()
{
  vtkSmartPointer<vtkMultiBlockDataSet> h = MakeGridHierarchy();
  MESHLOD_CHECK(CheckHierarchyLayout(h, true).empty());
  MESHLOD_CHECK_EQ(Level(h, 1)->GetNumberOfPolys(), 12);
  vtkNew<vtkLODGeomorph> filter;
  vtkNew<vtkTest::ErrorObserver> observer;
  filter->AddObserver(vtkCommand::WarningEvent, observer);
  filter->SetInputData(h);
  // count -> (triangles, points): 5 settles alone, 6 joins (-2), 9 joins (-2), 10 joins (-2).
  const vtkIdType expected[][3] = { { 18, 18, 16 }, { 17, 16, 15 }, { 16, 16, 15 }, { 15, 14, 14 },
    { 14, 14, 14 }, { 13, 12, 13 }, { 12, 12, 13 } };
  for (const auto& e : expected)
  {
    vtkPolyData* out = Run(filter, e[0]);
    MESHLOD_CHECK_EQ(out->GetNumberOfPolys(), e[1]);
    MESHLOD_CHECK_EQ(out->GetNumberOfPoints(), e[2]);
    const TriangleMesh mesh = testing::ToTriangleMesh(out);
    TriangleTopology topology;
    topology.Build(mesh);
    MESHLOD_CHECK_EQ(topology.CountEdges(mesh).NonManifold, 0);
    MESHLOD_CHECK_EQ(topology.EulerCharacteristic(mesh), 1);
    MESHLOD_CHECK(topology.IsConsistentlyOriented(mesh));
  }
  // 16 triangles: 5 and 6 merged at (1.5, 1.5) (point 5 of the output), with Height 7.5 (the
  // cluster's average), the others unchanged.
  vtkPolyData* out = Run(filter, 16);
  double x[3];
  out->GetPoint(5, x);
  MESHLOD_CHECK_EQ(x[0], 1.5);
  MESHLOD_CHECK_EQ(x[1], 1.5);
  MESHLOD_CHECK_EQ(out->GetPointData()->GetArray("Height")->GetTuple1(5), 7.5);
  MESHLOD_CHECK_EQ(out->GetPointData()->GetArray("Height")->GetTuple1(6), 7.0); // point 7
  out->GetPoint(8, x); // point 9: not settled yet
  MESHLOD_CHECK_EQ(x[0], 1.0);
  MESHLOD_CHECK_EQ(x[1], 2.0);
  MESHLOD_CHECK(!observer->GetWarning());

  // Out of range: clamped with a warning.
  out = Run(filter, 11);
  MESHLOD_CHECK(observer->GetWarning());
  MESHLOD_CHECK(out->GetPoints() == Level(h, 1)->GetPoints());
  observer->Clear();
  out = Run(filter, 40);
  MESHLOD_CHECK(observer->GetWarning());
  MESHLOD_CHECK(out->GetPoints() == Level(h, 0)->GetPoints());
  filter->SetTargetNumberOfTriangles(-7);
  MESHLOD_CHECK_EQ(filter->GetTargetNumberOfTriangles(), -1);
}

// An abort requested at the first progress report stops the build of the transition's order:
// the output is empty, no order is kept, and the next update builds it and gives the count.
void TestAbort(vtkMultiBlockDataSet* h)
{
  vtkNew<vtkLODGeomorph> filter;
  filter->SetInputData(h);
  const vtkIdType count = Level(h, 1)->GetNumberOfPolys() + 40;
  vtkNew<vtkCallbackCommand> abort;
  abort->SetCallback([](vtkObject* caller, unsigned long, void*, void*)
    { static_cast<vtkAlgorithm*>(caller)->AbortExecuteOn(); });
  const unsigned long tag = filter->AddObserver(vtkCommand::ProgressEvent, abort);
  MESHLOD_CHECK_EQ(Run(filter, count)->GetNumberOfPoints(), 0);
  filter->RemoveObserver(tag);
  filter->AbortExecuteOff();
  filter->Modified();
  MESHLOD_CHECK_EQ(Run(filter, count)->GetNumberOfPolys(), count);
}

// An exact count overrides LevelOfDetail: one beyond the coarsest level draws no warning then,
// and a NaN one no error.
void TestOverriddenLevelOfDetail(vtkMultiBlockDataSet* h)
{
  vtkNew<vtkLODGeomorph> filter;
  filter->SetInputData(h);
  filter->UsePipelineTimeOff();
  filter->SetLevelOfDetail(7.0);
  vtkNew<vtkTest::ErrorObserver> observer;
  filter->AddObserver(vtkCommand::WarningEvent, observer);
  const vtkIdType count = Level(h, 1)->GetNumberOfPolys() + 40;
  MESHLOD_CHECK_EQ(Run(filter, count)->GetNumberOfPolys(), count);
  MESHLOD_CHECK(!observer->GetWarning());
  // Nor is a NaN LevelOfDetail an error then (it is without the exact count).
  filter->AddObserver(vtkCommand::ErrorEvent, observer);
  filter->SetLevelOfDetail(std::numeric_limits<double>::quiet_NaN());
  MESHLOD_CHECK_EQ(Run(filter, count)->GetNumberOfPolys(), count);
  MESHLOD_CHECK(!observer->GetError());
  filter->SetTargetNumberOfTriangles(-1);
  filter->Update();
  MESHLOD_CHECK(observer->GetError());
}

void TestBackends(vtkMultiBlockDataSet* h)
{
  const auto runs = testing::RunWithBothBackends([&] {
    vtkNew<vtkLODGeomorph> filter;
    filter->SetInputData(h);
    return vtkSmartPointer<vtkPolyData>(Run(filter, Level(h, 1)->GetNumberOfPolys() + 40, 0.3));
  });
  MESHLOD_CHECK(testing::SameMesh(runs.first, runs.second));
}
} // namespace

int TestLODGeomorphExactCount(int, char*[])
{
  // An icosphere with Height = z and a cell label.
  vtkSmartPointer<vtkPolyData> sphere = testing::MakeIcosphere(3);
  vtkNew<vtkDoubleArray> height;
  height->SetName("Height");
  for (vtkIdType p = 0; p < sphere->GetNumberOfPoints(); ++p)
  {
    height->InsertNextValue(sphere->GetPoint(p)[2]);
  }
  sphere->GetPointData()->AddArray(height);
  vtkNew<vtkIntArray> cellLabel;
  cellLabel->SetName("CellLabel");
  for (vtkIdType c = 0; c < sphere->GetNumberOfCells(); ++c)
  {
    cellLabel->InsertNextValue(static_cast<int>(c));
  }
  sphere->GetCellData()->AddArray(cellLabel);
  testing::CollapseHierarchyOptions options;
  options.MaximumLevels = 3;
  options.MaximumFraction = 0.5;
  vtkSmartPointer<vtkMultiBlockDataSet> h = testing::MakeCollapseHierarchy(sphere, options);
  MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 3u);

  TestSweep(h);
  TestFraction(h);
  TestCluster();
  TestBackends(h);
  TestAbort(h);
  TestOverriddenLevelOfDetail(h);
  return testing::Result();
}
