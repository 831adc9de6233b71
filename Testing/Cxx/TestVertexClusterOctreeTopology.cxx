// vtkVertexClusterOctree's PreserveTopology on the isosurface of a noisy volume (a CT-like
// surface, rough at the scale of its edges): with it off the levels reach their target counts
// within the filter's tolerance and stay close to the input, nest, and do not depend on the
// thread count; with it on they keep the input's topology. The geomorph's exact counts reach
// the counts between the free levels. A surface that cannot be oriented reaches its counts
// with the topology kept.
#include "Core/PieceGenus.h"
#include "Core/Vector3.h"
#include "MeshLODHierarchyChecks.h"
#include "MeshLODSurfaceDistance.h"
#include "MeshLODTestCheck.h"
#include "MeshLODTestMeshes.h"
#include "vtkLODGeomorph.h"
#include "vtkVertexClusterOctree.h"

#include "vtkAppendPolyData.h"
#include "vtkCell.h"
#include "vtkCellArray.h"
#include "vtkFeatureEdges.h"
#include "vtkMath.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkParametricBoy.h"
#include "vtkParametricFunctionSource.h"
#include "vtkPolyData.h"
#include "vtkPolyDataConnectivityFilter.h"
#include "vtkSphereSource.h"
#include "vtkTestErrorObserver.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

namespace
{
using namespace meshlod;
using testing::Level;

// Levels at 10% and 1% of the input's triangles.
vtkSmartPointer<vtkMultiBlockDataSet> TenthAndHundredth(vtkPolyData* mesh, bool preserveTopology)
{
  vtkNew<vtkVertexClusterOctree> cluster;
  cluster->SetInputData(mesh);
  cluster->SetPreserveTopology(preserveTopology);
  cluster->SetLevelModeToTargetTriangleCounts();
  cluster->AddTargetTriangleCount(mesh->GetNumberOfPolys() / 10);
  cluster->AddTargetTriangleCount(mesh->GetNumberOfPolys() / 100);
  vtkNew<vtkTest::ErrorObserver> warnings;
  cluster->AddObserver(vtkCommand::WarningEvent, warnings);
  cluster->Update();
  if (!preserveTopology)
  {
    MESHLOD_CHECK(!warnings->GetWarning()); // no count missed
  }
  return cluster->GetHierarchy();
}

void TestFreeLevelsReachTheirCounts(vtkPolyData* mesh)
{
  vtkSmartPointer<vtkMultiBlockDataSet> h = TenthAndHundredth(mesh, false);
  MESHLOD_REQUIRE_EQ(h->GetNumberOfBlocks(), 3u);
  const vtkIdType input = mesh->GetNumberOfPolys();
  std::int64_t nonManifold = 0;
  for (unsigned int i = 1; i < 3; ++i)
  {
    const vtkIdType target = input / (i == 1 ? 10 : 100);
    const testing::MeshReport r = testing::InspectMesh(Level(h, i));
    const SurfaceDistance d = MeasureSurfaceDistance(mesh, Level(h, i));
    std::cerr << "free topology, target " << target << ": " << r.Triangles << " triangles, "
              << r.NonManifoldEdges << " non-manifold edges, Hausdorff " << d.HausdorffPercent()
              << "%, RMS " << d.RmsPercent() << "%\n";
    // The filter's own tolerance (a miss beyond it is warned about). Measured: 2,534 for 2,534
    // and 254 for 253; with PreserveTopology on, 3,508 and 712.
    MESHLOD_CHECK_LE(std::abs(r.Triangles - target), std::max<vtkIdType>(2, target / 50));
    MESHLOD_CHECK_EQ(r.DegenerateTriangles, 0);
    // A thin part folded flat keeps both its sides, one triangle in each orientation.
    MESHLOD_CHECK_EQ(r.SameOrientationDuplicates, 0);
    // Measured: Hausdorff 2.00% and 2.59%, RMS 0.31% and 0.53% of the diagonal, 1.02 and 0.99
    // times vtkQuadricClustering's Hausdorff distance at those counts (the Benchmarks' grid
    // search); with PreserveTopology on, the 712 triangles were at 10.8% (5.4 times).
    MESHLOD_CHECK_LT(d.HausdorffPercent(), i == 1 ? 2.6 : 3.4);
    MESHLOD_CHECK_LT(d.RmsPercent(), i == 1 ? 0.4 : 0.7);
    nonManifold += r.NonManifoldEdges;
  }
  // The repairs are lifted: some edges of the free levels have three or more triangles
  // (measured 42 and 5), as vtkQuadricClustering's output has.
  MESHLOD_CHECK_GT(nonManifold, 0);
  // Levels still nest, every triangle the image of a finer one.
  MESHLOD_CHECK_EQ(testing::CountCorrespondenceViolations(h), 0);

  // The same levels for any thread count.
  const auto both = testing::RunWithBothBackends(
    [&]() -> vtkSmartPointer<vtkPolyData>
    { return Level(TenthAndHundredth(mesh, false), 2); });
  MESHLOD_CHECK(testing::SameMesh(both.first, both.second));

  // The geomorph between the free levels: half-way, and exact counts swept over both
  // transitions. The free levels have non-manifold vertices, which no step of a transition
  // can repair; waiting for that made the steps after the first such vertex unstoppable (3 of
  // these 38 counts missed, by up to 1,140 triangles; now none, one allowed).
  vtkNew<vtkLODGeomorph> morph;
  morph->SetInputData(h);
  morph->SetLevelOfDetail(1.5);
  morph->Update();
  MESHLOD_CHECK_EQ(morph->GetOutput()->GetNumberOfPolys(), Level(h, 1)->GetNumberOfPolys());
  int missed = 0;
  for (unsigned int i = 0; i < 2; ++i)
  {
    const vtkIdType fine = Level(h, i)->GetNumberOfPolys();
    const vtkIdType coarse = Level(h, i + 1)->GetNumberOfPolys();
    for (int k = 1; k < 20; ++k)
    {
      const vtkIdType count = coarse + k * (fine - coarse) / 20;
      morph->SetTargetNumberOfTriangles(count);
      morph->Update();
      missed += std::abs(morph->GetOutput()->GetNumberOfPolys() - count) > 2 ? 1 : 0;
    }
  }
  MESHLOD_CHECK_LE(missed, 1);
}

void TestPreservedLevelsKeepTopology(vtkPolyData* mesh)
{
  vtkSmartPointer<vtkMultiBlockDataSet> h = TenthAndHundredth(mesh, true);
  MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 3u);
  for (unsigned int i = 1; i < h->GetNumberOfBlocks(); ++i)
  {
    const testing::MeshReport r = testing::InspectMesh(Level(h, i));
    MESHLOD_CHECK_EQ(r.NonManifoldEdges, 0);
    MESHLOD_CHECK_EQ(r.NonManifoldVertices, 0);
    MESHLOD_CHECK_EQ(r.BoundaryEdges, 0);
    MESHLOD_CHECK(r.ConsistentlyOriented);
  }
  MESHLOD_CHECK_EQ(testing::CountCorrespondenceViolations(h), 0);
}

// A closed surface of n x m squares of a parametrisation over [0, 2 pi)^2: a torus (radii 1 and
// `tube`), or with `klein` the figure-8 Klein bottle, whose last column joins the first upside
// down. Point (i, j) is i * m + j.
vtkSmartPointer<vtkPolyData> MakeTorusOrKleinBottle(int n, int m, bool klein, double tube = 0.35)
{
  std::vector<double> points;
  for (int i = 0; i < n; ++i)
  {
    for (int j = 0; j < m; ++j)
    {
      const double u = 2.0 * vtkMath::Pi() * i / n, v = 2.0 * vtkMath::Pi() * j / m;
      if (klein)
      {
        const double w = 2.0 + std::cos(u / 2) * std::sin(v) - std::sin(u / 2) * std::sin(2 * v);
        points.insert(points.end(), { w * std::cos(u), w * std::sin(u),
                                      std::sin(u / 2) * std::sin(v) + std::cos(u / 2) * std::sin(2 * v) });
      }
      else
      {
        const double w = 1.0 + tube * std::cos(v);
        points.insert(points.end(), { w * std::cos(u), w * std::sin(u), tube * std::sin(v) });
      }
    }
  }
  auto point = [&](int i, int j)
  {
    if (i == n)
    {
      i = 0;
      j = klein ? m - j : j; // upside down
    }
    return static_cast<long long>(i * m + (j % m + m) % m);
  };
  std::vector<long long> triangles;
  for (int i = 0; i < n; ++i)
  {
    for (int j = 0; j < m; ++j)
    {
      const long long a = point(i, j), b = point(i + 1, j), c = point(i + 1, j + 1),
                      d = point(i, j + 1);
      triangles.insert(triangles.end(), { a, b, c, a, c, d });
    }
  }
  return testing::MakePolyData(points, triangles);
}

// Two tori of 60 x 30 squares (tube radius 0.3), the second 2.6 further along x, sharing the
// point where the first's outer equator and the second's inner equator meet, (1.3, 0, 0).
vtkSmartPointer<vtkPolyData> MakeToriSharingPoint()
{
  // (The second torus's point (30, 0) is 30 * 30.)
  return testing::MakeTwinTouchingAt(MakeTorusOrKleinBottle(60, 30, false, 0.3), 0, 30 * 30,
    [](double x[3]) { x[0] += 2.6; }, false);
}

// The handles of a surface: HandleMeasures of each connected piece, summed (twice the genus of
// an orientable piece; spheres and disks count 0).
Id CountHandles(vtkPolyData* surface)
{
  std::vector<Id> triangles;
  vtkIdType n;
  const vtkIdType* ids;
  for (vtkIdType c = 0; c < surface->GetNumberOfPolys(); ++c)
  {
    surface->GetPolys()->GetCellAtId(c, n, ids);
    triangles.insert(triangles.end(), ids, ids + 3);
  }
  const Id points = static_cast<Id>(surface->GetNumberOfPoints());
  std::vector<Id> piece(points);
  std::iota(piece.begin(), piece.end(), Id(0));
  for (size_t k = 0; k < triangles.size(); ++k)
  {
    const Id a = FindRoot(piece, triangles[k]);
    const Id b = FindRoot(piece, triangles[k % 3 == 2 ? k - 2 : k + 1]);
    piece[std::max(a, b)] = std::min(a, b);
  }
  for (Id p = 0; p < points; ++p)
  {
    piece[p] = FindRoot(piece, p);
  }
  Id handles = 0;
  for (const PieceMeasure& m :
    HandleMeasures(triangles.data(), static_cast<Id>(triangles.size() / 3), piece, points))
  {
    handles += m.Measured ? m.Handles : 0;
  }
  return handles;
}

// The clusters' repairs are local: asked for fewer triangles than a shape allows, a level
// closed a handle between clusters that each kept their link (a torus of 3,600 triangles asked
// for 24 became a sphere of 16, a Klein bottle of 9,600 asked for 64 a sphere of 76), and on
// VTK's wavelet isosurface (11 pieces, 22 in CountHandles) the level asked for 1% kept 12, the
// levels at epsilon 0.05 and 0.3 of the diagonal 18. A trial level is now compared with the
// level before it: the clusters that hold a loop of edges around no triangles of their own are
// split, and a level that still closes a handle is not taken (the search takes a smaller
// epsilon; in the epsilon modes the level is cut at the largest one found that keeps every
// handle, and a warning says so). Two tori sharing a point count as two: asked for 720 and 72
// triangles, the second level lost one of them into the point (Euler characteristic -1 -> 0).
void TestHandlesStay()
{
  const struct
  {
    const char* Name;
    bool Klein;
    int N, M;
    vtkIdType Target, Most;
  } shapes[] = { { "torus", false, 60, 30, 24, 60 }, { "Klein bottle", true, 120, 40, 64, 120 } };
  for (const auto& shape : shapes)
  {
    vtkSmartPointer<vtkPolyData> mesh = MakeTorusOrKleinBottle(shape.N, shape.M, shape.Klein);
    MESHLOD_CHECK_EQ(testing::InspectMesh(mesh).EulerCharacteristic, 0);
    vtkNew<vtkVertexClusterOctree> cluster;
    cluster->SetInputData(mesh);
    cluster->SetLevelModeToTargetTriangleCounts();
    cluster->AddTargetTriangleCount(shape.Target);
    vtkNew<vtkTest::ErrorObserver> warnings;
    cluster->AddObserver(vtkCommand::WarningEvent, warnings);
    cluster->Update();
    vtkMultiBlockDataSet* h = cluster->GetHierarchy();
    MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 2u);
    const testing::MeshReport r = testing::InspectMesh(Level(h, 1));
    std::cerr << shape.Name << " asked for " << shape.Target << ": " << r.Triangles
              << " triangles, Euler characteristic " << r.EulerCharacteristic << "\n";
    MESHLOD_CHECK_EQ(r.EulerCharacteristic, 0);
    MESHLOD_CHECK_EQ(r.BoundaryEdges, 0);
    MESHLOD_CHECK_EQ(r.NonManifoldEdges, 0);
    MESHLOD_CHECK_EQ(r.NonManifoldVertices, 0);
    MESHLOD_CHECK_GT(r.Triangles, shape.Target); // measured: 48 and 100
    MESHLOD_CHECK_LE(r.Triangles, shape.Most);
    MESHLOD_CHECK(warnings->GetWarning()); // the count was missed
    MESHLOD_CHECK_EQ(testing::CountCorrespondenceViolations(h), 0);
  }

  {
    vtkSmartPointer<vtkPolyData> tori = MakeToriSharingPoint();
    MESHLOD_CHECK_EQ(CountHandles(tori), 4);
    vtkNew<vtkVertexClusterOctree> cluster;
    cluster->SetInputData(tori);
    cluster->SetLevelModeToTargetTriangleCounts();
    cluster->AddTargetTriangleCount(720);
    cluster->AddTargetTriangleCount(72);
    vtkNew<vtkTest::ErrorObserver> warnings;
    cluster->AddObserver(vtkCommand::WarningEvent, warnings);
    cluster->Update();
    vtkMultiBlockDataSet* h = cluster->GetHierarchy();
    MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 3u);
    for (unsigned int i = 1; i < h->GetNumberOfBlocks(); ++i)
    {
      const testing::MeshReport r = testing::InspectMesh(Level(h, i));
      std::cerr << "tori sharing a point, level " << i << ": " << r.Triangles
                << " triangles, Euler characteristic " << r.EulerCharacteristic << "\n";
      MESHLOD_CHECK_EQ(r.EulerCharacteristic, -1);
      MESHLOD_CHECK_EQ(CountHandles(Level(h, i)), 4);
    }
  }

  vtkSmartPointer<vtkPolyData> wavelet = testing::MakeWaveletIsosurface(20);
  const Id handles = CountHandles(wavelet);
  MESHLOD_CHECK_EQ(handles, 22);
  vtkSmartPointer<vtkMultiBlockDataSet> h = TenthAndHundredth(wavelet, true);
  for (unsigned int i = 1; i < h->GetNumberOfBlocks(); ++i)
  {
    std::cerr << "wavelet isosurface, level " << i << ": " << Level(h, i)->GetNumberOfPolys()
              << " triangles, " << CountHandles(Level(h, i)) << " in CountHandles\n";
    MESHLOD_CHECK_EQ(CountHandles(Level(h, i)), handles);
  }
  for (const double epsilon : { 0.05, 0.3 })
  {
    vtkNew<vtkVertexClusterOctree> cluster;
    cluster->SetInputData(wavelet);
    cluster->SetLevelModeToEpsilonList();
    cluster->AddEpsilonValue(epsilon);
    vtkNew<vtkTest::ErrorObserver> warnings;
    cluster->AddObserver(vtkCommand::WarningEvent, warnings);
    cluster->Update();
    vtkPolyData* level = Level(cluster->GetHierarchy(), 1);
    MESHLOD_CHECK(level != nullptr);
    if (!level)
    {
      continue;
    }
    const double asked = epsilon * wavelet->GetLength();
    std::cerr << "wavelet isosurface, epsilon " << epsilon << ": " << level->GetNumberOfPolys()
              << " triangles at epsilon " << cluster->GetLevelEpsilon(1) / asked
              << " of the one asked, " << CountHandles(level) << " in CountHandles\n";
    MESHLOD_CHECK_EQ(CountHandles(level), handles);
    MESHLOD_CHECK_LT(cluster->GetLevelEpsilon(1), asked);
    MESHLOD_CHECK(warnings->GetWarningMessage().find("closes a handle") != std::string::npos);
  }
}

// Spindles pinned at one apex: the clusters around the apex keep thousands of triangles,
// whose duplicates were found by comparing every pair of them (5,000 spindles: 1.6 s, now
// 0.13 s), and the spindles' thin sides fold flat (triangles on the same clusters in opposite
// orders). Every level without degenerate triangles or duplicates of one orientation, nested;
// the folded sides stay only with PreserveTopology off.
void TestSpindlesSharingApex()
{
  vtkSmartPointer<vtkPolyData> mesh = testing::MakeConesSharingApex(300, 8);
  for (const bool preserveTopology : { false, true })
  {
    vtkNew<vtkVertexClusterOctree> cluster;
    cluster->SetInputData(mesh);
    cluster->SetPreserveTopology(preserveTopology);
    cluster->SetLevelModeToTargetTriangleCounts();
    cluster->AddTargetTriangleCount(mesh->GetNumberOfPolys() / 4);
    cluster->AddTargetTriangleCount(mesh->GetNumberOfPolys() / 20);
    cluster->Update();
    vtkMultiBlockDataSet* h = cluster->GetHierarchy();
    MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 3u);
    std::int64_t opposite = 0;
    for (unsigned int i = 1; i < h->GetNumberOfBlocks(); ++i)
    {
      const testing::MeshReport r = testing::InspectMesh(Level(h, i));
      std::cerr << "spindles sharing an apex, PreserveTopology " << preserveTopology
                << ", level " << i << ": " << r.Triangles << " triangles, "
                << r.DuplicateTriangles << " duplicates\n";
      MESHLOD_CHECK_LT(r.Triangles, Level(h, i - 1)->GetNumberOfPolys());
      MESHLOD_CHECK_EQ(r.DegenerateTriangles, 0);
      MESHLOD_CHECK_EQ(r.SameOrientationDuplicates, 0);
      opposite += r.DuplicateTriangles;
    }
    MESHLOD_CHECK(preserveTopology ? opposite == 0 : opposite > 0);
    MESHLOD_CHECK_EQ(testing::CountCorrespondenceViolations(h), 0);
  }
}

// Boy's surface cannot be oriented: its triangles' windings disagree along a seam, where the
// summed normal of the input around a cluster cancels and says nothing about a triangle's
// facing. The fold test compares a triangle touching a seam with its own previous self there;
// against the summed normal it refused most clusters along the seam, and the levels kept 2,522
// and 1,520 triangles asked for 1,940 and 194 (now 2,096 and 194). The levels keep the input's
// topology all the same (closed, manifold, Euler characteristic 1) and nest.
void TestNonOrientableSurface()
{
  vtkNew<vtkParametricBoy> boy;
  vtkNew<vtkParametricFunctionSource> source;
  source->SetParametricFunction(boy);
  source->SetUResolution(100);
  source->SetVResolution(100);
  source->GenerateNormalsOff();
  vtkSmartPointer<vtkPolyData> mesh = testing::TriangulateAndClean(source);
  vtkSmartPointer<vtkMultiBlockDataSet> h = TenthAndHundredth(mesh, true);
  MESHLOD_REQUIRE_EQ(h->GetNumberOfBlocks(), 3u);
  const testing::MeshReport input = testing::InspectMesh(Level(h, 0));
  MESHLOD_CHECK(!input.ConsistentlyOriented);
  for (unsigned int i = 1; i < 3; ++i)
  {
    const vtkIdType target = mesh->GetNumberOfPolys() / (i == 1 ? 10 : 100);
    const testing::MeshReport r = testing::InspectMesh(Level(h, i));
    const SurfaceDistance d = MeasureSurfaceDistance(mesh, Level(h, i));
    std::cerr << "Boy's surface, target " << target << ": " << r.Triangles << " triangles, "
              << "Hausdorff " << d.HausdorffPercent() << "%, RMS " << d.RmsPercent() << "%\n";
    MESHLOD_CHECK_LE(r.Triangles, target + target / 4);
    MESHLOD_CHECK_EQ(r.NonManifoldEdges, 0);
    MESHLOD_CHECK_EQ(r.NonManifoldVertices, 0);
    MESHLOD_CHECK_EQ(r.BoundaryEdges, 0);
    MESHLOD_CHECK_EQ(r.DegenerateTriangles, 0);
    MESHLOD_CHECK_EQ(r.DuplicateTriangles, 0);
    MESHLOD_CHECK_EQ(r.EulerCharacteristic, input.EulerCharacteristic);
    // Measured: Hausdorff 0.51% and 3.3%, RMS 0.091% and 0.74% of the diagonal.
    MESHLOD_CHECK_LT(d.HausdorffPercent(), i == 1 ? 0.8 : 5.0);
    MESHLOD_CHECK_LT(d.RmsPercent(), i == 1 ? 0.15 : 1.1);
  }
  MESHLOD_CHECK_EQ(testing::CountCorrespondenceViolations(h), 0);
}

// A sphere of 28,560 triangles with two small closed pieces beside it: a ball of radius 0.02
// half a radius away and a speck of radius 0.01 just above it (0.002). A piece that a level
// merges whole vanishes, and the input there is then as far from the level as the nearest
// surface that stays: the far ball is kept on every level (it vanished at 1%, 14.1% of the
// diagonal from the level; now 0.95%), the speck only until the level's surface passes within
// twice the epsilon of it (it vanishes at the coarsest level).
void TestFarPiecesStay()
{
  auto sphere = [](double radius, double x, double y, int resolution)
  {
    vtkNew<vtkSphereSource> source;
    source->SetRadius(radius);
    source->SetCenter(x, y, 0.0);
    source->SetThetaResolution(resolution);
    source->SetPhiResolution(resolution);
    source->Update();
    return vtkSmartPointer<vtkPolyData>(source->GetOutput());
  };
  vtkNew<vtkAppendPolyData> append;
  append->AddInputData(sphere(1.0, 0.0, 0.0, 120));
  append->AddInputData(sphere(0.02, 1.5, 0.0, 12));
  append->AddInputData(sphere(0.01, 0.0, 1.012, 8));
  vtkSmartPointer<vtkPolyData> mesh = testing::TriangulateAndClean(append);
  vtkNew<vtkVertexClusterOctree> cluster;
  cluster->SetInputData(mesh);
  cluster->SetLevelModeToTargetTriangleCounts();
  for (const int share : { 10, 100, 400 })
  {
    cluster->AddTargetTriangleCount(mesh->GetNumberOfPolys() / share);
  }
  cluster->Update();
  vtkMultiBlockDataSet* h = cluster->GetHierarchy();
  MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 4u);
  // Triangles with their centroid within `within` of (x, y, 0).
  auto trianglesNear = [](vtkPolyData* level, double x, double y, double within)
  {
    vtkIdType count = 0;
    for (vtkIdType t = 0; t < level->GetNumberOfPolys(); ++t)
    {
      double centroid[3] = { 0.0, 0.0, 0.0 };
      for (int c = 0; c < 3; ++c)
      {
        double p[3];
        level->GetPoint(level->GetCell(t)->GetPointId(c), p);
        for (int i = 0; i < 3; ++i)
        {
          centroid[i] += p[i] / 3.0;
        }
      }
      const double at[3] = { x, y, 0.0 };
      count += Distance2(centroid, at) < within * within ? 1 : 0;
    }
    return count;
  };
  for (unsigned int i = 1; i < h->GetNumberOfBlocks(); ++i)
  {
    vtkPolyData* level = Level(h, i);
    const SurfaceDistance d = MeasureSurfaceDistance(mesh, level);
    std::cerr << "pieces beside a sphere, level " << i << ": " << level->GetNumberOfPolys()
              << " triangles, " << trianglesNear(level, 1.5, 0.0, 0.1) << " on the far ball, "
              << trianglesNear(level, 0.0, 1.012, 0.02) << " on the speck, Hausdorff "
              << d.HausdorffPercent() << "%\n";
    MESHLOD_CHECK_GE(trianglesNear(level, 1.5, 0.0, 0.1), 4);
    MESHLOD_CHECK_EQ(testing::InspectMesh(level).NonManifoldEdges, 0);
    if (i == 2)
    {
      MESHLOD_CHECK_LT(d.HausdorffPercent(), 1.5);
    }
  }
  MESHLOD_CHECK_EQ(trianglesNear(Level(h, 3), 0.0, 1.012, 0.02), 0);
  MESHLOD_CHECK_EQ(testing::CountCorrespondenceViolations(h), 0);
}

// An icosphere with 20 flat closed tetrahedra around it, at an epsilon of 1e-30 of the diagonal.
// The tetrahedra have no error, so each merges whole and would vanish, but it lies far from
// the level's surface: every one stays (the level keeps the input, with a warning). The grid
// that finds the kept surface near a vanishing piece has cells of twice the epsilon, here 1e29
// cells across the mesh, beyond any 64-bit integer (the cell numbers are clamped).
void TestTinyEpsilonKeepsFlatPieces()
{
  vtkSmartPointer<vtkPolyData> sphere = testing::MakeIcosphere(3);
  std::vector<double> points;
  std::vector<long long> triangles;
  for (vtkIdType p = 0; p < sphere->GetNumberOfPoints(); ++p)
  {
    double x[3];
    sphere->GetPoint(p, x);
    points.insert(points.end(), x, x + 3);
  }
  for (vtkIdType t = 0; t < sphere->GetNumberOfPolys(); ++t)
  {
    for (int c = 0; c < 3; ++c)
    {
      triangles.push_back(sphere->GetCell(t)->GetPointId(c));
    }
  }
  constexpr int Pieces = 20;
  for (int i = 0; i < Pieces; ++i)
  {
    const double angle = 2.0 * vtkMath::Pi() * i / Pieces;
    const double centre[3] = { 2.5 * std::cos(angle), 2.5 * std::sin(angle), 0.1 * (i % 3) };
    const double corners[4][2] = { { 0, 0 }, { 1, 0 }, { 0, 1 }, { 0.3, 0.3 } };
    const long long first = static_cast<long long>(points.size() / 3);
    for (const auto& corner : corners)
    {
      points.insert(
        points.end(), { centre[0] + 0.05 * corner[0], centre[1] + 0.05 * corner[1], centre[2] });
    }
    for (const long long tri : { 0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2 })
    {
      triangles.push_back(first + tri);
    }
  }
  vtkSmartPointer<vtkPolyData> mesh = testing::MakePolyData(points, triangles);
  vtkNew<vtkVertexClusterOctree> cluster;
  vtkNew<vtkTest::ErrorObserver> warnings;
  cluster->AddObserver(vtkCommand::WarningEvent, warnings);
  cluster->SetInputData(mesh);
  cluster->SetLevelModeToEpsilonList();
  cluster->AddEpsilonValue(1e-30);
  cluster->Update();
  vtkMultiBlockDataSet* h = cluster->GetHierarchy();
  MESHLOD_REQUIRE_EQ(h->GetNumberOfBlocks(), 2u);
  MESHLOD_CHECK_EQ(Level(h, 1)->GetNumberOfPolys(), sphere->GetNumberOfPolys() + 4 * Pieces);
  MESHLOD_CHECK(warnings->GetWarningMessage().find("keeps the") != std::string::npos);
}

// The number of boundary loops of a surface.
int CountBoundaryLoops(vtkPolyData* surface)
{
  vtkNew<vtkFeatureEdges> edges;
  edges->SetInputData(surface);
  edges->BoundaryEdgesOn();
  edges->FeatureEdgesOff();
  edges->NonManifoldEdgesOff();
  edges->ManifoldEdgesOff();
  vtkNew<vtkPolyDataConnectivityFilter> loops;
  loops->SetInputConnection(edges->GetOutputPort());
  loops->SetExtractionModeToAllRegions();
  loops->Update();
  return loops->GetNumberOfExtractedRegions();
}

// VTK's wavelet isosurface on [-60, 60]^3 (241,392 triangles) is cut open by the volume's faces
// in 39 boundary loops, small ones where a bulge pokes through a face. A cluster holding a whole
// loop caps it, and the input's boundary there is then as far from the level as the surface
// that caps it: asked for 1%, the level closed 11 loops, one 3.7% of the diagonal from the input
// there. A loop now closes only where its vertices lie within twice the epsilon of the level's
// triangles around them: 30 loops kept, 2.0% (its clusters err by up to 1.4%).
void TestHolesStayOpen()
{
  vtkSmartPointer<vtkPolyData> mesh = testing::MakeWaveletIsosurface(60);
  const int loops = CountBoundaryLoops(mesh);
  MESHLOD_CHECK_EQ(loops, 39);
  vtkSmartPointer<vtkMultiBlockDataSet> h = TenthAndHundredth(mesh, true);
  MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 3u);
  for (unsigned int i = 1; i < h->GetNumberOfBlocks(); ++i)
  {
    const SurfaceDistance d = MeasureSurfaceDistance(mesh, Level(h, i));
    std::cerr << "wavelet isosurface, level " << i << ": " << Level(h, i)->GetNumberOfPolys()
              << " triangles, " << CountBoundaryLoops(Level(h, i)) << " boundary loops, Hausdorff "
              << d.HausdorffPercent() << "%\n";
    MESHLOD_CHECK_GE(CountBoundaryLoops(Level(h, i)), i == 1 ? loops : 30);
    MESHLOD_CHECK_LT(d.HausdorffPercent(), i == 1 ? 0.3 : 2.5);
  }
  MESHLOD_CHECK_EQ(testing::CountCorrespondenceViolations(h), 0);
}

void TestSetting()
{
  vtkNew<vtkVertexClusterOctree> cluster;
  MESHLOD_CHECK(cluster->GetPreserveTopology());
  cluster->PreserveTopologyOff();
  std::ostringstream printed;
  cluster->Print(printed);
  MESHLOD_CHECK(printed.str().find("PreserveTopology: Off") != std::string::npos);
}
} // namespace

int TestVertexClusterOctreeTopology(int, char*[])
{
  // 25,344 triangles, closed, noise of one grid step.
  vtkSmartPointer<vtkPolyData> mesh = testing::MakeNoisyIsosurface(60, 1.0, 5);
  MESHLOD_CHECK_EQ(testing::InspectMesh(mesh).BoundaryEdges, 0);
  TestFreeLevelsReachTheirCounts(mesh);
  TestPreservedLevelsKeepTopology(mesh);
  TestSpindlesSharingApex();
  TestNonOrientableSurface();
  TestHandlesStay();
  TestFarPiecesStay();
  TestTinyEpsilonKeepsFlatPieces();
  TestHolesStayOpen();
  TestSetting();
  return meshlod::testing::Result();
}
