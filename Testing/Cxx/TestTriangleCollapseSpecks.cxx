// vtkTriangleCollapseDecimation's PreserveTopology: with it off, small closed pieces (the specks
// of a noisy isosurface) vanish into points of no cell, which MorphTargetId still maps to, and
// the levels reach counts that every piece kept as a tetrahedron makes unreachable; with it on
// (the default) every piece stays.
#include "vtkTriangleCollapseDecimation.h"

#include "MeshLODHierarchy.h"
#include "MeshLODHierarchyChecks.h"
#include "MeshLODSurfaceDistance.h"
#include "MeshLODTestCheck.h"
#include "MeshLODTestMeshes.h"
#include "vtkLODGeomorph.h"

#include "vtkAppendPolyData.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkTestErrorObserver.h"
#include "vtkTransform.h"
#include "vtkTransformPolyDataFilter.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace
{
using namespace meshlod;
using testing::Level;

struct Run
{
  vtkSmartPointer<vtkMultiBlockDataSet> Hierarchy;
  bool Warned = false;
  std::string Warning;
};

Run Decimate(vtkPolyData* mesh, bool preserveTopology, double reduction,
  const std::function<void(vtkTriangleCollapseDecimation*)>& configure = nullptr)
{
  vtkNew<vtkTriangleCollapseDecimation> decimate;
  if (configure)
  {
    configure(decimate);
  }
  decimate->SetInputData(mesh);
  decimate->SetPreserveTopology(preserveTopology);
  decimate->SetTargetReduction(reduction);
  vtkNew<vtkTest::ErrorObserver> warnings;
  decimate->AddObserver(vtkCommand::WarningEvent, warnings);
  decimate->Update();
  return Run{ decimate->GetHierarchy(), warnings->GetWarning() != 0,
    warnings->GetWarningMessage() };
}

// Per point, its connected piece (the lowest point id in it); `pieces` gets their number.
std::vector<vtkIdType> PieceOfPoint(vtkPolyData* mesh, vtkIdType& pieces)
{
  std::vector<vtkIdType> piece(mesh->GetNumberOfPoints());
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    piece[i] = i;
  }
  const auto root = [&](vtkIdType v) {
    while (piece[v] != v)
    {
      v = piece[v] = piece[piece[v]];
    }
    return v;
  };
  std::vector<char> used(piece.size(), 0);
  for (const testing::TriangleIds& t : testing::Triangles(mesh))
  {
    for (int k = 0; k < 3; ++k)
    {
      used[t[k]] = 1;
      const vtkIdType a = root(t[0]), b = root(t[k]);
      piece[std::max(a, b)] = std::min(a, b);
    }
  }
  pieces = 0;
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    piece[i] = root(i);
    pieces += piece[i] == i && used[i] ? 1 : 0; // pieces of triangles only
  }
  return piece;
}

// Where each point of level 0 ends in the coarsest level (MorphTargetId chained).
std::vector<vtkIdType> ChainToCoarsest(vtkMultiBlockDataSet* h)
{
  std::vector<vtkIdType> at(Level(h, 0)->GetNumberOfPoints());
  for (vtkIdType i = 0; i < static_cast<vtkIdType>(at.size()); ++i)
  {
    at[i] = i;
  }
  for (unsigned int l = 0; l + 1 < h->GetNumberOfBlocks(); ++l)
  {
    vtkDataArray* target = Level(h, l)->GetPointData()->GetArray(names::MorphTargetId);
    for (vtkIdType& p : at)
    {
      p = static_cast<vtkIdType>(target->GetTuple1(p));
    }
  }
  return at;
}

std::int64_t UnusedPoints(vtkPolyData* mesh)
{
  std::vector<char> used(mesh->GetNumberOfPoints(), 0);
  for (const testing::TriangleIds& t : testing::Triangles(mesh))
  {
    used[t[0]] = used[t[1]] = used[t[2]] = 1;
  }
  std::int64_t unused = 0;
  for (const char u : used)
  {
    unused += u ? 0 : 1;
  }
  return unused;
}

// A sphere of 1,280 triangles and, beside it, a small octahedron; a point array x + 10 y.
vtkSmartPointer<vtkPolyData> SphereAndSpeck()
{
  vtkSmartPointer<vtkPolyData> sphere = testing::MakeIcosphere(3);
  vtkNew<vtkTransform> move;
  move->Translate(1.5, 0.0, 0.0);
  move->Scale(0.02, 0.02, 0.02);
  vtkNew<vtkTransformPolyDataFilter> speck;
  speck->SetInputData(testing::MakeOctahedron());
  speck->SetTransform(move);
  vtkNew<vtkAppendPolyData> append;
  append->AddInputData(sphere);
  append->AddInputConnection(speck->GetOutputPort());
  append->Update();
  vtkSmartPointer<vtkPolyData> mesh = append->GetOutput();
  vtkNew<vtkDoubleArray> value;
  value->SetName("Value");
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    double x[3];
    mesh->GetPoint(i, x);
    value->InsertNextValue(x[0] + 10.0 * x[1]);
  }
  mesh->GetPointData()->AddArray(value);
  return mesh;
}

void TestSpeckVanishesIntoOnePoint()
{
  vtkSmartPointer<vtkPolyData> mesh = SphereAndSpeck();
  MESHLOD_CHECK_EQ(mesh->GetNumberOfPolys(), 1288);

  // Default: the speck stays (the octahedron shrinks to a tetrahedron at most).
  const Run kept = Decimate(mesh, true, 0.95);
  vtkPolyData* keptLast = Level(kept.Hierarchy, kept.Hierarchy->GetNumberOfBlocks() - 1);
  vtkIdType pieces = 0;
  PieceOfPoint(keptLast, pieces);
  MESHLOD_CHECK_EQ(pieces, 2);
  MESHLOD_CHECK_EQ(UnusedPoints(keptLast), 0);
  MESHLOD_CHECK_EQ(testing::InspectMesh(keptLast).EulerCharacteristic, 4);

  // Off: it vanishes whole, into one point of no cell at its centre, in every level from the
  // first (its cost is far below any collapse of the sphere).
  const Run run = Decimate(mesh, false, 0.95);
  vtkMultiBlockDataSet* h = run.Hierarchy;
  MESHLOD_CHECK(!run.Warned);
  MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 9u);
  for (unsigned int l = 1; l < h->GetNumberOfBlocks(); ++l)
  {
    vtkPolyData* level = Level(h, l);
    MESHLOD_CHECK_EQ(UnusedPoints(level), 1);
    const testing::MeshReport r = testing::InspectMesh(level);
    MESHLOD_CHECK_EQ(r.EulerCharacteristic, 2); // the sphere alone
    MESHLOD_CHECK_EQ(r.NonManifoldEdges + r.BoundaryEdges + r.DegenerateTriangles, 0);
    MESHLOD_CHECK(level->GetPointData()->GetArray("Value") != nullptr);
  }
  // 1,288 triangles asked for 5%: 64 (1,280 - 8 of the speck would be 1,216 otherwise lost).
  MESHLOD_CHECK_EQ(Level(h, h->GetNumberOfBlocks() - 1)->GetNumberOfPolys(), 64);
  MESHLOD_CHECK_EQ(testing::CountCorrespondenceViolations(h), 0);

  // The speck's six points all map to the one unused point, which stands at its centre with
  // the mean of their values.
  vtkPolyData* last = Level(h, h->GetNumberOfBlocks() - 1);
  const std::vector<vtkIdType> at = ChainToCoarsest(h);
  const vtkIdType first = 642; // the icosphere's points come first
  const vtkIdType point = at[first];
  std::vector<char> used(last->GetNumberOfPoints(), 0);
  for (const testing::TriangleIds& t : testing::Triangles(last))
  {
    used[t[0]] = used[t[1]] = used[t[2]] = 1;
  }
  MESHLOD_CHECK(!used[point]);
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    MESHLOD_CHECK_EQ(at[i] == point, i >= first);
  }
  double x[3];
  last->GetPoint(point, x);
  MESHLOD_CHECK_LT(std::hypot(x[0] - 1.5, x[1], x[2]), 1e-6);
  const double value = last->GetPointData()->GetArray("Value")->GetTuple1(point);
  MESHLOD_CHECK_LT(std::abs(value - 1.5), 1e-5); // the mean of the speck's values
}

// The input's largest piece never vanishes, so no level is empty: alone, an octahedron shrinks
// to a tetrahedron; beside another, the first (lowest point ids) stays as that tetrahedron.
void TestLargestPieceStays()
{
  const Run alone = Decimate(testing::MakeOctahedron(), false, 0.99);
  vtkPolyData* last = Level(alone.Hierarchy, alone.Hierarchy->GetNumberOfBlocks() - 1);
  MESHLOD_CHECK_EQ(last->GetNumberOfPolys(), 4);
  MESHLOD_CHECK_EQ(UnusedPoints(last), 0);

  vtkNew<vtkTransform> move;
  move->Translate(3.0, 0.0, 0.0);
  vtkNew<vtkTransformPolyDataFilter> second;
  second->SetInputData(testing::MakeOctahedron());
  second->SetTransform(move);
  vtkNew<vtkAppendPolyData> append;
  append->AddInputData(testing::MakeOctahedron());
  append->AddInputConnection(second->GetOutputPort());
  append->Update();
  const Run pair = Decimate(append->GetOutput(), false, 0.99);
  last = Level(pair.Hierarchy, pair.Hierarchy->GetNumberOfBlocks() - 1);
  MESHLOD_CHECK_EQ(last->GetNumberOfPolys(), 4);
  MESHLOD_CHECK_EQ(UnusedPoints(last), 1);
  const std::vector<vtkIdType> at = ChainToCoarsest(pair.Hierarchy);
  for (vtkIdType i = 0; i < 12; ++i)
  {
    double x[3];
    last->GetPoint(at[i], x);
    MESHLOD_CHECK_EQ(x[0] > 1.5, i >= 6); // the second octahedron's points end at its point
  }
}

// The coarsest level of `h` keeps the main surface of `mesh` alone: every other piece (closed,
// genus 0) vanished into a point of no cell, which all of its points and only they map to, and
// the rest kept its genus.
void CheckVanishedPieces(vtkPolyData* mesh, vtkMultiBlockDataSet* h, const char* what)
{
  vtkIdType pieces = 0;
  const std::vector<vtkIdType> piece = PieceOfPoint(mesh, pieces);
  const std::int64_t euler = testing::InspectMesh(mesh).EulerCharacteristic;
  vtkPolyData* last = Level(h, h->GetNumberOfBlocks() - 1);
  vtkIdType lastPieces = 0;
  PieceOfPoint(last, lastPieces);
  const std::int64_t vanished = UnusedPoints(last);
  const testing::MeshReport r = testing::InspectMesh(last);
  std::cerr << what << ": " << r.Triangles << " triangles, " << lastPieces << " pieces, "
            << vanished << " vanished of " << pieces << ", Euler characteristic "
            << r.EulerCharacteristic << " of " << euler << "\n";
  MESHLOD_CHECK_EQ(lastPieces, 1); // the main surface (the points have no triangle)
  MESHLOD_CHECK_EQ(vanished, pieces - 1);
  // Each vanished piece was a sphere (characteristic 2); the rest keep their genus.
  MESHLOD_CHECK_EQ(r.EulerCharacteristic, euler - 2 * vanished);
  MESHLOD_CHECK_EQ(r.NonManifoldEdges + r.BoundaryEdges + r.DegenerateTriangles, 0);
  MESHLOD_CHECK_EQ(testing::CountCorrespondenceViolations(h), 0);

  // Every point of a vanished piece maps to that piece's point, and only they do.
  const std::vector<vtkIdType> at = ChainToCoarsest(h);
  std::vector<char> used(last->GetNumberOfPoints(), 0);
  for (const testing::TriangleIds& t : testing::Triangles(last))
  {
    used[t[0]] = used[t[1]] = used[t[2]] = 1;
  }
  std::map<vtkIdType, vtkIdType> pieceOfVanished; // unused point -> its input piece
  std::int64_t mixed = 0;
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    if (used[at[i]])
    {
      continue;
    }
    const auto found = pieceOfVanished.emplace(at[i], piece[i]);
    mixed += found.first->second != piece[i] ? 1 : 0;
  }
  MESHLOD_CHECK_EQ(mixed, 0);
  MESHLOD_CHECK_EQ(static_cast<std::int64_t>(pieceOfVanished.size()), vanished);
}

// The isosurface of a noisy volume: its specks keep the default levels far above the 1%
// target; with PreserveTopology off every target is met, each vanished speck leaves one point
// that all of its points map to, and the coarsest level is the main surface alone.
void TestNoisyIsosurface()
{
  vtkSmartPointer<vtkPolyData> mesh = testing::MakeNoisyIsosurface(60, 1.0, 5);
  const vtkIdType input = mesh->GetNumberOfPolys();
  MESHLOD_CHECK_EQ(input, 25344);
  vtkIdType pieces = 0;
  const std::vector<vtkIdType> piece = PieceOfPoint(mesh, pieces);
  const std::int64_t euler = testing::InspectMesh(mesh).EulerCharacteristic;
  std::cerr << "noisy isosurface: " << pieces << " pieces, Euler characteristic " << euler
            << "\n";

  const Run kept = Decimate(mesh, true, 0.99);
  vtkPolyData* keptLast = Level(kept.Hierarchy, kept.Hierarchy->GetNumberOfBlocks() - 1);
  // Short of the target, and told why.
  MESHLOD_CHECK(kept.Warning.find("each of its 80 connected pieces keeps at least a tetrahedron, "
                                  "or a triangle if open, while PreserveTopology is on") !=
    std::string::npos);
  MESHLOD_CHECK_GE(keptLast->GetNumberOfPolys(), 4 * (pieces - 1));
  MESHLOD_CHECK_EQ(testing::InspectMesh(keptLast).EulerCharacteristic, euler);

  const Run run = Decimate(mesh, false, 0.99);
  vtkMultiBlockDataSet* h = run.Hierarchy;
  MESHLOD_CHECK(!run.Warned);
  MESHLOD_REQUIRE_EQ(h->GetNumberOfBlocks(), 9u);
  // Counts spaced geometrically to 1%, each within 4 triangles of its target (a vanishing
  // speck may remove more than are left; here the specks are gone by level 3).
  const double ratio = std::pow(0.01, 1.0 / 8.0);
  for (unsigned int l = 1; l < 9; ++l)
  {
    const double target = input * std::pow(ratio, l);
    MESHLOD_CHECK_LE(std::abs(Level(h, l)->GetNumberOfPolys() - target), 4.0);
  }
  vtkPolyData* last = Level(h, 8);
  CheckVanishedPieces(mesh, h, "greedy");

  // Measured: 252 triangles for 253, at Hausdorff 2.63% and RMS 0.52% of the diagonal (1.02
  // and 0.99 times vtkQuadricDecimation's at that count); the default's coarsest level has 402
  // triangles, 316 of them in 79 specks, at 13% and 4.5%.
  const SurfaceDistance d = MeasureSurfaceDistance(mesh, last);
  std::cerr << "free 1%: Hausdorff " << d.HausdorffPercent() << "%, RMS " << d.RmsPercent()
            << "%\n";
  MESHLOD_CHECK_LT(d.HausdorffPercent(), 3.5);
  MESHLOD_CHECK_LT(d.RmsPercent(), 0.6);

  // The same levels for any thread count.
  const auto both = testing::RunWithBothBackends(
    [&]() -> vtkSmartPointer<vtkPolyData> { return Level(Decimate(mesh, false, 0.99).Hierarchy, 8); });
  MESHLOD_CHECK(testing::SameMesh(both.first, both.second));

  // A geomorph shrinks each speck to its point: exact counts swept over the first transition,
  // where the specks vanish (measured: one of 19 missed, by 3 triangles).
  vtkNew<vtkLODGeomorph> morph;
  morph->SetInputData(h);
  int missed = 0;
  const vtkIdType fine = Level(h, 0)->GetNumberOfPolys(), coarse = Level(h, 1)->GetNumberOfPolys();
  for (int k = 1; k < 20; ++k)
  {
    const vtkIdType count = coarse + k * (fine - coarse) / 20;
    morph->SetTargetNumberOfTriangles(count);
    morph->Update();
    missed += std::abs(morph->GetOutput()->GetNumberOfPolys() - count) > 2 ? 1 : 0;
  }
  MESHLOD_CHECK_LE(missed, 2);
  morph->SetTargetNumberOfTriangles(-1);
  morph->SetLevelOfDetail(1.0);
  morph->Update();
  MESHLOD_CHECK_EQ(morph->GetOutput()->GetNumberOfPolys(), coarse);
}

// The other schedule and method let specks vanish too (the triangle collapses of both leave
// them as octahedra, under paper 000's valence rule). The curvature method, whose triangle
// collapses run out on this rough surface, falls back on edges once it stalls and reaches its
// count (it had stopped at 542 triangles for 253).
void TestOtherSchedules()
{
  vtkSmartPointer<vtkPolyData> mesh = testing::MakeNoisyIsosurface(60, 1.0, 5);
  const Run sets = Decimate(mesh, false, 0.99,
    [](vtkTriangleCollapseDecimation* d) { d->SetScheduleToIndependentSets(); });
  CheckVanishedPieces(mesh, sets.Hierarchy, "independent sets");
  const Run curvature = Decimate(
    mesh, false, 0.99, [](vtkTriangleCollapseDecimation* d) { d->SetMethodToCurvature(); });
  CheckVanishedPieces(mesh, curvature.Hierarchy, "curvature");
  MESHLOD_CHECK(!curvature.Warned);
  vtkPolyData* last = Level(curvature.Hierarchy, curvature.Hierarchy->GetNumberOfBlocks() - 1);
  MESHLOD_CHECK_LE(std::abs(last->GetNumberOfPolys() - 253), 4);
  // Measured: Hausdorff 5.3% and RMS 1.2% of the diagonal (2.1 and 2.2 times
  // vtkQuadricDecimation's at that count).
  const SurfaceDistance d = MeasureSurfaceDistance(mesh, last);
  MESHLOD_CHECK_LT(d.HausdorffPercent(), 6.5);
  MESHLOD_CHECK_LT(d.RmsPercent(), 1.5);
}

// Open pieces stay with PreserveTopology off (they may be the faces of a flat-shaded model that
// its normals keep apart): a lone triangle above a terrain is still there at 1%.
void TestOpenPiecesStay()
{
  vtkSmartPointer<vtkPolyData> grid = testing::MakeTerrain(20); // 800 triangles on [-1, 1]^2
  vtkSmartPointer<vtkPolyData> debris =
    testing::MakePolyData({ 0, 0, 1, 0.03, 0, 1, 0, 0.03, 1 }, { 0, 1, 2 });
  vtkNew<vtkAppendPolyData> append;
  append->AddInputData(grid);
  append->AddInputData(debris);
  append->Update();
  const Run run = Decimate(append->GetOutput(), false, 0.99);
  vtkPolyData* last = Level(run.Hierarchy, run.Hierarchy->GetNumberOfBlocks() - 1);
  MESHLOD_CHECK_EQ(UnusedPoints(last), 0);
  vtkIdType pieces = 0;
  PieceOfPoint(last, pieces);
  MESHLOD_CHECK_EQ(pieces, 2);
}

void TestSetting()
{
  vtkNew<vtkTriangleCollapseDecimation> decimate;
  MESHLOD_CHECK(decimate->GetPreserveTopology());
  decimate->PreserveTopologyOff();
  std::ostringstream printed;
  decimate->Print(printed);
  MESHLOD_CHECK(printed.str().find("PreserveTopology: Off") != std::string::npos);
}
} // namespace

int TestTriangleCollapseSpecks(int, char*[])
{
  TestSpeckVanishesIntoOnePoint();
  TestLargestPieceStays();
  TestNoisyIsosurface();
  TestOtherSchedules();
  TestOpenPiecesStay();
  TestSetting();
  return meshlod::testing::Result();
}
