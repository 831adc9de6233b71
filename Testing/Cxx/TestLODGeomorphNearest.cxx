// vtkLODGeomorph without morph data: the nearest-vertex correspondence (hand-made cases with
// known partners, conflicts), the blend and merge between two vtkQuadricDecimation outputs,
// the correspondence cache, and the same output for every SMP backend.
#include "vtkLODGeomorph.h"

#include "MeshLODHierarchyChecks.h"
#include "MeshLODHierarchy.h"
#include "MeshLODNearestCorrespondence.h"
#include "MeshLODSurfaceDistance.h"
#include "MeshLODTestCheck.h"
#include "MeshLODTestHierarchies.h"
#include "MeshLODTestMeshes.h"

#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkIntArray.h"
#include "vtkMath.h"
#include "vtkMinimalStandardRandomSequence.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkQuadricDecimation.h"
#include "vtkSMPTools.h"
#include "vtkStaticPointLocator.h"
#include "vtkTestErrorObserver.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace
{
using namespace meshlod;
using testing::Level;

vtkPolyData* Run(vtkLODGeomorph* filter, double lod)
{
  filter->SetLevelOfDetail(lod);
  filter->Update();
  return filter->GetOutput();
}

// Largest distance from a point of `a` to the nearest point of `b`.
double OneSidedPointDistance(vtkPolyData* a, vtkPolyData* b)
{
  vtkNew<vtkStaticPointLocator> locator;
  locator->SetDataSet(b);
  locator->BuildLocator();
  double worst = 0.0;
  for (vtkIdType p = 0; p < a->GetNumberOfPoints(); ++p)
  {
    double x[3], y[3];
    a->GetPoint(p, x);
    b->GetPoint(locator->FindClosestPoint(x), y);
    worst = std::max(worst, std::sqrt(vtkMath::Distance2BetweenPoints(x, y)));
  }
  return worst;
}

// Fine: the 2x2 grid (points j * 3 + i at (i, j)). Coarse: a square on (0, 0), (2.2, 0),
// (0, 2.2), (2.2, 2.2). Partners: coarse corners take the fine corners 0, 2, 6, 8; the others
// their nearest corner: 1, 3, 4 -> 0; 5 -> 1; 7 -> 2.
void TestSmallCorrespondence()
{
  vtkSmartPointer<vtkPolyData> fine = testing::MakeGrid(2, 2);
  vtkSmartPointer<vtkPolyData> coarse =
    testing::MakePolyData({ 0, 0, 0, 2.2, 0, 0, 0, 2.2, 0, 2.2, 2.2, 0 }, { 0, 1, 3, 0, 3, 2 });
  std::vector<Id> partner;
  NearestVertexCorrespondence(fine->GetPoints(), coarse->GetPoints(), partner);
  MESHLOD_CHECK(partner == std::vector<Id>({ 0, 0, 1, 0, 0, 1, 2, 2, 3 }));

  // At t -> 1: the groups {0, 1, 3, 4}, {2, 5}, {6, 7}, {8} merge (they are joined by edges)
  // and only the two triangles of the coarse square are left.
  vtkSmartPointer<vtkMultiBlockDataSet> h = testing::GatherLevels({ fine, coarse });
  vtkNew<vtkLODGeomorph> filter;
  filter->SetInputData(h);
  vtkPolyData* out = Run(filter, 1.0 - 1e-9);
  MESHLOD_CHECK_EQ(filter->GetActualCorrespondence(), vtkLODGeomorph::NEAREST_VERTICES);
  MESHLOD_CHECK_EQ(out->GetNumberOfPoints(), 4);
  MESHLOD_CHECK_EQ(out->GetNumberOfPolys(), 2);
  MESHLOD_CHECK_LE(OneSidedPointDistance(out, coarse), 1e-8);
  MESHLOD_CHECK_LE(OneSidedPointDistance(coarse, out), 1e-8);
  // Halfway: nothing merges, the grid keeps its connectivity.
  out = Run(filter, 0.5);
  MESHLOD_CHECK_EQ(out->GetNumberOfPoints(), 9);
  MESHLOD_CHECK(out->GetPolys() == fine->GetPolys());
  double x[3];
  out->GetPoint(5, x); // (2, 1) halfway to (2.2, 0)
  MESHLOD_CHECK_EQ(x[0], 2.1);
  MESHLOD_CHECK_EQ(x[1], 0.5);

  // Coarse points 0 (0.9, 1) and 1 (1.45, 0.9) both nearest to fine point 4; 2 (2.05, 1) takes
  // 5. Point 0 is nearer and keeps 4; point 1 takes its nearest free fine point, 1 (at 1.006),
  // although fine point 1 is a little nearer to coarse point 0 (1.005): without that, coarse
  // point 1 would be reached by nobody.
  vtkNew<vtkPoints> three;
  three->InsertNextPoint(0.9, 1.0, 0.0);
  three->InsertNextPoint(1.45, 0.9, 0.0);
  three->InsertNextPoint(2.05, 1.0, 0.0);
  NearestVertexCorrespondence(fine->GetPoints(), three, partner);
  MESHLOD_CHECK_EQ(partner[4], 0);
  MESHLOD_CHECK_EQ(partner[5], 2);
  MESHLOD_CHECK_EQ(partner[1], 1);
  MESHLOD_CHECK_EQ(partner[0], 0);
}

// The correspondence as its documentation states it, by comparing every pair of points.
std::vector<Id> BruteForceCorrespondence(vtkPoints* fine, vtkPoints* coarse)
{
  const vtkIdType nf = fine->GetNumberOfPoints(), nc = coarse->GetNumberOfPoints();
  auto d2 = [&](vtkIdType c, vtkIdType f) {
    double x[3], y[3];
    coarse->GetPoint(c, x);
    fine->GetPoint(f, y);
    return vtkMath::Distance2BetweenPoints(x, y);
  };
  // The nearest fine point to coarse point c (a free one with `freeOnly`), the lowest id on
  // ties; -1 if none.
  auto nearest = [&](vtkIdType c, const std::vector<Id>& owner, bool freeOnly) {
    vtkIdType best = -1;
    for (vtkIdType f = 0; f < nf; ++f)
    {
      if ((!freeOnly || owner[f] == InvalidId) && (best < 0 || d2(c, f) < d2(c, best)))
      {
        best = f;
      }
    }
    return best;
  };
  std::vector<Id> owner(nf, InvalidId), losers;
  for (vtkIdType c = 0; c < nc; ++c)
  {
    const vtkIdType f = nearest(c, owner, false);
    if (owner[f] == InvalidId || d2(c, f) < d2(owner[f], f))
    {
      if (owner[f] != InvalidId)
      {
        losers.push_back(owner[f]);
      }
      owner[f] = static_cast<Id>(c);
    }
    else
    {
      losers.push_back(static_cast<Id>(c));
    }
  }
  std::sort(losers.begin(), losers.end());
  for (const Id c : losers)
  {
    const vtkIdType f = nearest(c, owner, true);
    if (f >= 0)
    {
      owner[f] = c;
    }
  }
  for (vtkIdType f = 0; f < nf; ++f)
  {
    if (owner[f] == InvalidId)
    {
      vtkIdType best = 0;
      for (vtkIdType c = 1; c < nc; ++c)
      {
        best = d2(c, f) < d2(best, f) ? c : best;
      }
      owner[f] = static_cast<Id>(best);
    }
  }
  return owner;
}

// Random clouds where most coarse points lose their first pick: the coarse cloud far from the
// fine one (all pick the same few fine points), larger than it (some reach no fine point), and
// mixed in. The correspondence must be the documented one (the free fine points of the losers
// come from a k-d tree; asking a locator for ever more points took minutes at a few thousand).
void TestCorrespondenceAgainstBruteForce()
{
  vtkNew<vtkMinimalStandardRandomSequence> random;
  random->SetSeed(11);
  auto cloud = [&](vtkIdType n, double shift) {
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    for (vtkIdType p = 0; p < n; ++p)
    {
      double x[3];
      for (double& v : x)
      {
        v = random->GetNextRangeValue(-1.0, 1.0);
      }
      x[0] += shift;
      points->InsertNextPoint(x);
    }
    return vtkSmartPointer<vtkPoints>(points);
  };
  struct Case
  {
    vtkIdType Fine, Coarse;
    double Shift;
  };
  for (const Case& c : { Case{ 600, 300, 10.0 }, Case{ 300, 600, 0.0 }, Case{ 500, 400, 0.0 },
         Case{ 400, 400, 1.5 }, Case{ 700, 50, 3.0 } })
  {
    vtkSmartPointer<vtkPoints> fine = cloud(c.Fine, 0.0);
    vtkSmartPointer<vtkPoints> coarse = cloud(c.Coarse, c.Shift);
    std::vector<Id> partner;
    NearestVertexCorrespondence(fine, coarse, partner);
    MESHLOD_CHECK(partner == BruteForceCorrespondence(fine, coarse));
    // Every coarse point is reached when the fine cloud has at least as many points.
    std::vector<bool> reached(c.Coarse, false);
    for (const Id q : partner)
    {
      reached[q] = true;
    }
    MESHLOD_CHECK_EQ(std::count(reached.begin(), reached.end(), true), std::min(c.Fine, c.Coarse));
  }
}

// Levels far apart (every coarse point's pick lost to a few fine points): an abort requested at
// the first progress report stops the correspondence midway. Nothing is cached then, and the
// next update builds it whole.
void TestAbortFarApart()
{
  vtkSmartPointer<vtkPolyData> fine = testing::MakeIcosphere(5);
  vtkSmartPointer<vtkPolyData> coarse = testing::MakeIcosphere(4);
  vtkPoints* points = coarse->GetPoints();
  for (vtkIdType p = 0; p < points->GetNumberOfPoints(); ++p)
  {
    double x[3];
    points->GetPoint(p, x);
    x[0] += 10.0;
    points->SetPoint(p, x);
  }
  vtkNew<vtkLODGeomorph> filter;
  filter->SetInputData(testing::GatherLevels({ fine, coarse }));
  filter->UsePipelineTimeOff();
  filter->SetLevelOfDetail(0.5);
  vtkNew<vtkCallbackCommand> abort;
  abort->SetCallback([](vtkObject* caller, unsigned long, void*, void*)
    { static_cast<vtkAlgorithm*>(caller)->AbortExecuteOn(); });
  const unsigned long tag = filter->AddObserver(vtkCommand::ProgressEvent, abort);
  filter->Update();
  MESHLOD_CHECK_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);
  MESHLOD_CHECK_EQ(filter->GetNumberOfCorrespondenceBuilds(), 0);
  filter->RemoveObserver(tag);
  filter->AbortExecuteOff();
  filter->Modified();
  filter->Update();
  MESHLOD_CHECK_EQ(filter->GetOutput()->GetNumberOfPoints(), fine->GetNumberOfPoints());
  MESHLOD_CHECK_EQ(filter->GetNumberOfCorrespondenceBuilds(), 1);
}

// Two decimations of an isosurface, with point data.
vtkSmartPointer<vtkMultiBlockDataSet> MakeDecimatedPair(vtkPolyData* surface)
{
  vtkNew<vtkQuadricDecimation> half;
  half->SetInputData(surface);
  half->SetTargetReduction(0.5);
  half->Update();
  vtkNew<vtkQuadricDecimation> tenth;
  tenth->SetInputData(surface);
  tenth->SetTargetReduction(0.9);
  tenth->Update();
  std::vector<vtkPolyData*> levels = { half->GetOutput(), tenth->GetOutput() };
  for (vtkPolyData* level : levels)
  {
    vtkNew<vtkDoubleArray> height;
    height->SetName("Height");
    for (vtkIdType p = 0; p < level->GetNumberOfPoints(); ++p)
    {
      height->InsertNextValue(level->GetPoint(p)[2]);
    }
    level->GetPointData()->AddArray(height);
  }
  return testing::GatherLevels(levels);
}

void TestDecimatedPair()
{
  vtkSmartPointer<vtkPolyData> surface = testing::MakeIsosurface(testing::Field::Metaballs, 48);
  vtkSmartPointer<vtkMultiBlockDataSet> h = MakeDecimatedPair(surface);
  vtkPolyData* fine = Level(h, 0);
  vtkPolyData* coarse = Level(h, 1);
  const double diagonal = fine->GetLength();
  const double epsilon = 1e-4 * diagonal; // the default MergeTolerance

  vtkNew<vtkLODGeomorph> filter;
  filter->SetInputData(h);
  vtkNew<vtkTest::ErrorObserver> observer;
  filter->AddObserver(vtkCommand::ErrorEvent, observer);
  filter->AddObserver(vtkCommand::WarningEvent, observer);

  // t = 0 and t = 1: the two meshes.
  MESHLOD_CHECK(Run(filter, 0.0)->GetPoints() == fine->GetPoints());
  MESHLOD_CHECK(Run(filter, 1.0)->GetPoints() == coarse->GetPoints());
  MESHLOD_CHECK_EQ(filter->GetNumberOfCorrespondenceBuilds(), 0);

  // Next to t = 0: the fine mesh within epsilon, nothing merged.
  vtkPolyData* out = Run(filter, 1e-9);
  MESHLOD_CHECK_EQ(filter->GetNumberOfCorrespondenceBuilds(), 1);
  MESHLOD_CHECK_EQ(out->GetNumberOfPoints(), fine->GetNumberOfPoints());
  MESHLOD_CHECK(out->GetPolys() == fine->GetPolys());
  MESHLOD_CHECK_LE(OneSidedPointDistance(out, fine), epsilon);

  // Next to t = 1: the coarse mesh within epsilon. Every point on a coarse point, every coarse
  // point reached (fine has more points), the fine points that met merged.
  out = Run(filter, 1.0 - 1e-9);
  MESHLOD_CHECK_LE(OneSidedPointDistance(out, coarse), epsilon);
  MESHLOD_CHECK_LE(OneSidedPointDistance(coarse, out), epsilon);
  MESHLOD_CHECK_LT(out->GetNumberOfPoints(), fine->GetNumberOfPoints());
  MESHLOD_CHECK_LT(out->GetNumberOfPolys(), fine->GetNumberOfPolys());
  const SurfaceDistance d = MeasureSurfaceDistance(coarse, out);
  std::cout << "t -> 1: " << out->GetNumberOfPoints() << " points (coarse "
            << coarse->GetNumberOfPoints() << "), " << out->GetNumberOfPolys()
            << " triangles (coarse " << coarse->GetNumberOfPolys() << "), Hausdorff "
            << d.HausdorffPercent() << " %, RMS " << d.RmsPercent() << " %\n";
  MESHLOD_CHECK_LE(d.HausdorffPercent(), 1.0);
  // No triangle repeats a point.
  const TriangleMesh mesh = testing::ToTriangleMesh(out);
  int repeated = 0;
  for (Id t = 0; t < mesh.GetNumberOfTriangles(); ++t)
  {
    const Id* tri = mesh.Triangle(t);
    repeated += tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0];
  }
  MESHLOD_CHECK_EQ(repeated, 0);

  // Halfway: points and Height blended with the partners.
  out = Run(filter, 0.5);
  vtkDataArray* height = out->GetPointData()->GetArray("Height");
  MESHLOD_CHECK(height != nullptr);
  int wrong = 0;
  for (vtkIdType p = 0; height && p < out->GetNumberOfPoints(); ++p)
  {
    wrong += std::abs(height->GetTuple1(p) - out->GetPoint(p)[2]) > 1e-6;
  }
  MESHLOD_CHECK_EQ(wrong, 0);

  // Only L changed: the correspondence was built once.
  for (const double lod : { 0.1, 0.3, 0.7, 0.9 })
  {
    Run(filter, lod);
  }
  MESHLOD_CHECK_EQ(filter->GetNumberOfCorrespondenceBuilds(), 1);
  // A larger tolerance merges more.
  const vtkIdType defaultPoints = Run(filter, 0.9)->GetNumberOfPoints();
  filter->SetMergeTolerance(0.01);
  MESHLOD_CHECK_LT(Run(filter, 0.9)->GetNumberOfPoints(), defaultPoints);
  MESHLOD_CHECK_EQ(filter->GetNumberOfCorrespondenceBuilds(), 1);
  MESHLOD_CHECK(!observer->GetWarning());
  // A tolerance near the mesh's size merges the surface away: warned, once for that value.
  filter->SetMergeTolerance(0.5);
  MESHLOD_CHECK_LT(Run(filter, 0.5)->GetNumberOfPolys(), coarse->GetNumberOfPolys());
  MESHLOD_CHECK(observer->GetWarning());
  MESHLOD_CHECK(observer->GetWarningMessage().find("MergeTolerance 0.5") != std::string::npos);
  observer->Clear();
  Run(filter, 0.6);
  MESHLOD_CHECK(!observer->GetWarning());
  // Another tolerance too large, though it merges the same edges: warned for that value too
  // (the check ran only when the merged edges changed).
  filter->SetMergeTolerance(0.9);
  Run(filter, 0.6);
  MESHLOD_CHECK(observer->GetWarningMessage().find("MergeTolerance 0.9") != std::string::npos);
  observer->Clear();
  filter->SetMergeTolerance(1e-4);
  // The input changed: built again.
  coarse->GetPoints()->Modified();
  Run(filter, 0.5);
  MESHLOD_CHECK_EQ(filter->GetNumberOfCorrespondenceBuilds(), 2);

  // An exact count needs the morph arrays: the next level instead, with a warning.
  MESHLOD_CHECK(!observer->GetWarning());
  filter->SetTargetNumberOfTriangles(fine->GetNumberOfPolys() - 10);
  out = Run(filter, 0.0);
  MESHLOD_CHECK(observer->GetWarning());
  MESHLOD_CHECK(out->GetPoints() == coarse->GetPoints());
  filter->SetTargetNumberOfTriangles(-1);
  MESHLOD_CHECK(!observer->GetError());

  // Asking for the morph arrays on meshes without them: an error.
  filter->SetCorrespondenceToMorphArrays();
  Run(filter, 0.5);
  MESHLOD_CHECK(observer->GetError());
  MESHLOD_CHECK_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);
  observer->Clear();

  // Same output for the sequential and the default backend.
  const auto runs = testing::RunWithBothBackends([&] {
    vtkNew<vtkLODGeomorph> f;
    f->SetInputData(h);
    return vtkSmartPointer<vtkPolyData>(Run(f, 0.97));
  });
  MESHLOD_CHECK(testing::SameMesh(runs.first, runs.second));
}

// A morph hierarchy read with the nearest-vertex correspondence instead.
void TestForcedNearest()
{
  testing::CollapseHierarchyOptions options;
  options.MaximumLevels = 3;
  vtkSmartPointer<vtkMultiBlockDataSet> h =
    testing::MakeCollapseHierarchy(testing::MakeIcosphere(3), options);
  vtkNew<vtkLODGeomorph> filter;
  filter->SetInputData(h);
  filter->SetCorrespondenceToNearestVertices();
  vtkPolyData* out = Run(filter, 1.5);
  MESHLOD_CHECK_EQ(filter->GetActualCorrespondence(), vtkLODGeomorph::NEAREST_VERTICES);
  MESHLOD_CHECK_EQ(filter->GetNumberOfCorrespondenceBuilds(), 1);
  MESHLOD_CHECK(out->GetPointData()->GetArray(names::MorphTargetId) == nullptr);
  MESHLOD_CHECK_EQ(out->GetNumberOfPoints(), Level(h, 1)->GetNumberOfPoints());
  Run(filter, 0.5);
  MESHLOD_CHECK_EQ(filter->GetNumberOfCorrespondenceBuilds(), 2);
  Run(filter, 1.25);
  MESHLOD_CHECK_EQ(filter->GetNumberOfCorrespondenceBuilds(), 2);
}
} // namespace

int TestLODGeomorphNearest(int, char*[])
{
  TestSmallCorrespondence();
  TestCorrespondenceAgainstBruteForce();
  TestAbortFarApart();
  TestDecimatedPair();
  TestForcedNearest();
  return testing::Result();
}
