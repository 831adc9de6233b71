// vtkVertexClusterOctree on particular shapes: flat-faced solids (single-precision ones too),
// sheets meeting along curves, open boundaries (sharp tips too), non-manifold input, rough
// planes, noisy terrains and spheres, thin tubes and high-valence fans; exact results where the
// shape allows, counts and distances otherwise.
#include "MeshLODHierarchy.h"
#include "MeshLODHierarchyChecks.h"
#include "MeshLODSurfaceDistance.h"
#include "MeshLODTestCheck.h"
#include "MeshLODTestMeshes.h"
#include "vtkVertexClusterOctree.h"

#include "vtkCellArray.h"
#include "vtkCleanPolyData.h"
#include "vtkCommand.h"
#include "vtkCylinderSource.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkLine.h"
#include "vtkLinearSubdivisionFilter.h"
#include "vtkMath.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPlatonicSolidSource.h"
#include "vtkPolyData.h"
#include "vtkSphereSource.h"
#include "vtkTestErrorObserver.h"
#include "vtkTriangleFilter.h"
#include "vtkTubeFilter.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace
{
using namespace meshlod;
using testing::Level;
using testing::Triangles;
using Triangle = testing::TriangleIds;

// The hierarchy of `cluster` on `mesh` at 10% and 1% of its triangles (target-count mode).
vtkMultiBlockDataSet* AtTenthAndHundredth(vtkVertexClusterOctree* cluster, vtkPolyData* mesh)
{
  cluster->SetInputData(mesh);
  cluster->SetLevelModeToTargetTriangleCounts();
  cluster->AddTargetTriangleCount(mesh->GetNumberOfPolys() / 10);
  cluster->AddTargetTriangleCount(mesh->GetNumberOfPolys() / 100);
  cluster->Update();
  return cluster->GetHierarchy();
}

//------------------------------------------------------------------------------
// Where a cluster's quadric minimiser would flip a triangle, one of its vertices that flips none
// stands for it (OctreeNodes.cxx, Evaluate): on a metaballs isosurface the 1% level's distances
// to the input fell by a quarter, since fewer clusters are split again.
void TestFlipFreeRepresentatives()
{
  const testing::Field field = testing::Field::Metaballs;
  vtkNew<vtkCleanPolyData> clean;
  clean->SetInputData(testing::MakeIsosurface(field, testing::ResolutionForTriangles(field, 40000)));
  clean->Update();
  vtkPolyData* mesh = clean->GetOutput();
  const vtkIdType triangles = mesh->GetNumberOfPolys();
  vtkNew<vtkVertexClusterOctree> filter;
  vtkMultiBlockDataSet* h = AtTenthAndHundredth(filter, mesh);
  MESHLOD_REQUIRE_EQ(h->GetNumberOfBlocks(), 3u);
  for (unsigned int i = 1; i < 3; ++i)
  {
    const SurfaceDistance d = MeasureSurfaceDistance(mesh, Level(h, i));
    std::cerr << "  metaballs (" << triangles << " triangles), level " << i << ": "
              << Level(h, i)->GetNumberOfPolys() << " triangles, Hausdorff "
              << d.HausdorffPercent() << "%, RMS " << d.RmsPercent() << "%\n";
    if (i == 2)
    {
      // 404 triangles at 0.63% and 0.157% (with every such cluster refused: 400 at 0.83% and
      // 0.200%).
      MESHLOD_CHECK_LE(d.HausdorffPercent(), 0.72);
      MESHLOD_CHECK_LE(d.RmsPercent(), 0.175);
    }
  }
  MESHLOD_CHECK_EQ(testing::CountRepeatedPointTriangles(h), 0);
}

//------------------------------------------------------------------------------
// A solid of flat faces, finely subdivided (an icosahedron of 20,480 triangles) and asked for
// 1%: clusters inside a face or along an edge have no error, but once clusters of the axis-
// aligned cells reach across the faces' edges they cut the corners, and fold refusals keep
// the count far above the target anyway. The level backs off to an epsilon with more
// triangles when it is far more accurate for its count: it keeps the solid exactly (it was 390
// triangles at 8% Hausdorff distance; vtkQuadricClustering's at 780 triangles is 0.21%).
void TestFlatFacedSolid()
{
  vtkNew<vtkPlatonicSolidSource> solid;
  solid->SetSolidTypeToIcosahedron();
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(solid->GetOutputPort());
  vtkNew<vtkLinearSubdivisionFilter> subdivide;
  subdivide->SetInputConnection(triangles->GetOutputPort());
  subdivide->SetNumberOfSubdivisions(5);
  vtkNew<vtkCleanPolyData> clean;
  clean->SetInputConnection(subdivide->GetOutputPort());
  clean->Update();
  vtkPolyData* mesh = clean->GetOutput();
  MESHLOD_CHECK_EQ(mesh->GetNumberOfPolys(), 20480);
  vtkNew<vtkVertexClusterOctree> filter;
  vtkNew<vtkTest::ErrorObserver> observer;
  filter->AddObserver(vtkCommand::WarningEvent, observer); // the missed count
  filter->SetInputData(mesh);
  filter->SetLevelModeToTargetTriangleCounts();
  filter->AddTargetTriangleCount(2048);
  filter->AddTargetTriangleCount(205);
  filter->Update();
  vtkMultiBlockDataSet* h = filter->GetHierarchy();
  MESHLOD_REQUIRE_EQ(h->GetNumberOfBlocks(), 3u);
  vtkPolyData* coarse = Level(h, 2);
  const SurfaceDistance d = MeasureSurfaceDistance(mesh, coarse);
  std::cerr << "  subdivided icosahedron asked for 205: " << coarse->GetNumberOfPolys()
            << " triangles, Hausdorff " << d.HausdorffPercent() << "%\n";
  MESHLOD_CHECK_LT(coarse->GetNumberOfPolys(), Level(h, 1)->GetNumberOfPolys());
  MESHLOD_CHECK_LE(d.HausdorffPercent(), 1e-4); // rounding of the float points only
  MESHLOD_CHECK(observer->GetWarningMessage().find("asked for 205 triangles") !=
    std::string::npos);
  MESHLOD_CHECK_EQ(testing::CountRepeatedPointTriangles(h), 0);
}

//------------------------------------------------------------------------------
// A flat-faced solid whose points are single precision (an octagonal prism of 7,168 triangles):
// the planes of one face's triangles differ by the rounding of their points, and its clusters
// evaluated to errors of rounding size in no order. Such errors count as none, so flat clusters
// merge smallest first and the search for 1% finds levels without error (it took 32 triangles
// at 7% of the diagonal, the prism's corner edges cut, when these errors ordered the merges).
// (For target counts only: in the epsilon modes a cluster's error stays within epsilon.)
void TestSinglePrecisionPrism()
{
  vtkNew<vtkCylinderSource> prism;
  prism->SetResolution(8);
  prism->CappingOn();
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(prism->GetOutputPort());
  vtkNew<vtkCleanPolyData> merged; // the caps' points are the sides' again
  merged->SetInputConnection(triangles->GetOutputPort());
  vtkNew<vtkLinearSubdivisionFilter> subdivide;
  subdivide->SetInputConnection(merged->GetOutputPort());
  subdivide->SetNumberOfSubdivisions(4);
  subdivide->Update();
  vtkPolyData* mesh = subdivide->GetOutput();
  MESHLOD_REQUIRE_EQ(mesh->GetNumberOfPolys(), 7168);
  MESHLOD_CHECK_EQ(mesh->GetPoints()->GetDataType(), VTK_FLOAT);
  vtkNew<vtkVertexClusterOctree> filter;
  vtkNew<vtkTest::ErrorObserver> observer;
  filter->AddObserver(vtkCommand::WarningEvent, observer); // a count missed by a few
  vtkMultiBlockDataSet* h = AtTenthAndHundredth(filter, mesh);
  MESHLOD_REQUIRE_EQ(h->GetNumberOfBlocks(), 3u);
  for (unsigned int i = 1; i < 3; ++i)
  {
    const vtkIdType target = mesh->GetNumberOfPolys() / (i == 1 ? 10 : 100);
    const vtkIdType count = Level(h, i)->GetNumberOfPolys();
    const SurfaceDistance d = MeasureSurfaceDistance(mesh, Level(h, i));
    std::cerr << "  octagonal prism asked for " << target << ": " << count
              << " triangles, Hausdorff " << d.HausdorffPercent() << "%\n";
    MESHLOD_CHECK_LE(d.HausdorffPercent(), 1e-4); // rounding of the float points only
    MESHLOD_CHECK_GE(count, target / 2); // (732 and 72)
    MESHLOD_CHECK_LE(count, 2 * target);
  }
  MESHLOD_CHECK_EQ(testing::CountRepeatedPointTriangles(h), 0);
  // In the epsilon modes such errors still count as they are: every cluster stays within its
  // level's epsilon (epsilon 0 merges the exactly flat clusters only: 4,816 triangles, not 56).
  vtkNew<vtkVertexClusterOctree> byEpsilon;
  byEpsilon->SetInputData(mesh);
  byEpsilon->SetLevelModeToEpsilonList();
  const double epsilons[3] = { 0.0, 1e-8, 1e-7 };
  for (const double epsilon : epsilons)
  {
    byEpsilon->AddEpsilonValue(epsilon);
  }
  byEpsilon->Update();
  vtkMultiBlockDataSet* levels = byEpsilon->GetHierarchy();
  MESHLOD_REQUIRE_EQ(levels->GetNumberOfBlocks(), 4u);
  for (unsigned int i = 1; i < 4; ++i)
  {
    const double error = Level(levels, i)
                           ->GetFieldData()
                           ->GetArray(names::EstimatedError)
                           ->GetComponent(0, 0);
    MESHLOD_CHECK_LE(error, epsilons[i - 1] * mesh->GetLength());
  }
  MESHLOD_CHECK_GT(Level(levels, 1)->GetNumberOfPolys(), 1000);
}

//------------------------------------------------------------------------------
// Sheets meeting along a curve (a unit sphere with its equatorial disk: the equator's edges
// have three triangles). Clusters may hold one open piece of the curve, so both targets are
// reached (the curve's vertices never merged before: 1,950 and 1,826 triangles were kept when
// 1,372 and 137 were asked). Every level keeps the topology: the Euler characteristic, no
// boundary, the curve with three triangles on each of its edges, on the disk's plane.
void TestSheetsAlongCurve()
{
  vtkSmartPointer<vtkPolyData> input = testing::MakeSphereWithEquatorialDisk(96, 47, 24);
  const testing::MeshReport before = testing::InspectMesh(input);
  const vtkIdType n = input->GetNumberOfPolys();
  vtkNew<vtkVertexClusterOctree> filter;
  vtkMultiBlockDataSet* h = AtTenthAndHundredth(filter, input);
  MESHLOD_REQUIRE_EQ(h->GetNumberOfBlocks(), 3u);
  MESHLOD_CHECK_EQ(testing::CountRepeatedPointTriangles(h), 0);
  MESHLOD_CHECK_EQ(testing::CountCorrespondenceViolations(h), 0);
  SurfaceDistanceOptions options;
  options.SamplesPerSurface = 20000;
  for (unsigned int i = 1; i < 3; ++i)
  {
    vtkPolyData* level = Level(h, i);
    const SurfaceDistance d = MeasureSurfaceDistance(input, level, options);
    const testing::MeshReport report = testing::InspectMesh(level);
    std::cerr << "  sphere with an equatorial disk (" << n << " triangles), level " << i << ": "
              << level->GetNumberOfPolys() << " triangles, " << report.NonManifoldEdges
              << " curve edges, Hausdorff " << d.HausdorffPercent() << "%, RMS "
              << d.RmsPercent() << "%\n";
    const vtkIdType asked = i == 1 ? n / 10 : n / 100;
    MESHLOD_CHECK_LE(level->GetNumberOfPolys(), asked + asked / 4);
    MESHLOD_CHECK_EQ(report.EulerCharacteristic, before.EulerCharacteristic);
    MESHLOD_CHECK_EQ(report.BoundaryEdges, 0);
    MESHLOD_CHECK_GE(report.NonManifoldEdges, 3);
    MESHLOD_CHECK_LT(d.HausdorffPercent(), i == 1 ? 1.0 : 6.0);
    // Each curve edge has three triangles and lies near the disk's plane z = 0: within 0.04%
    // of the radius at 10%, 4% at 1% (where the whole curve has 19 edges).
    const double off = i == 1 ? 1e-3 : 0.05;
    for (const auto& edge : testing::EdgeTriangleCounts(level))
    {
      MESHLOD_CHECK(edge.second == 2 || edge.second == 3);
      if (edge.second == 3)
      {
        MESHLOD_CHECK_LT(std::abs(level->GetPoint(edge.first.first)[2]), off);
        MESHLOD_CHECK_LT(std::abs(level->GetPoint(edge.first.second)[2]), off);
      }
    }
  }
}

//------------------------------------------------------------------------------
// Open boundaries: every boundary point of every level lies on the input's boundary.
std::vector<std::array<double, 6>> BoundarySegments(vtkPolyData* poly)
{
  std::map<std::pair<vtkIdType, vtkIdType>, int> uses;
  for (const Triangle& t : Triangles(poly))
  {
    for (int k = 0; k < 3; ++k)
    {
      ++uses[{ std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3]) }];
    }
  }
  std::vector<std::array<double, 6>> segments;
  for (const auto& edge : uses)
  {
    if (edge.second == 1)
    {
      std::array<double, 6> s;
      poly->GetPoint(edge.first.first, s.data());
      poly->GetPoint(edge.first.second, s.data() + 3);
      segments.push_back(s);
    }
  }
  return segments;
}

double DistanceToSegments(const double x[3], const std::vector<std::array<double, 6>>& segments)
{
  double best = VTK_DOUBLE_MAX;
  for (const auto& s : segments)
  {
    double t;
    double closest[3];
    best =
      std::min(best, std::sqrt(vtkLine::DistanceToLine(x, s.data(), s.data() + 3, t, closest)));
  }
  return best;
}

void TestOpenBoundary(vtkPolyData* mesh, const char* what)
{
  vtkNew<vtkVertexClusterOctree> filter;
  filter->SetInputData(mesh);
  filter->SetNumberOfLevels(4);
  filter->SetEpsilon(0.001);
  filter->Update();
  vtkMultiBlockDataSet* h = filter->GetHierarchy();
  MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 5u);
  const std::vector<std::array<double, 6>> input = BoundarySegments(mesh);
  for (unsigned int i = 1; i < h->GetNumberOfBlocks(); ++i)
  {
    vtkPolyData* level = Level(h, i);
    double worst = 0.0;
    for (const auto& s : BoundarySegments(level))
    {
      worst = std::max(worst, DistanceToSegments(s.data(), input));
      worst = std::max(worst, DistanceToSegments(s.data() + 3, input));
    }
    if (worst > 1e-6 * mesh->GetLength())
    {
      std::cerr << what << " level " << i << ": boundary point " << worst << " off the input's\n";
    }
    MESHLOD_CHECK_LE(worst, 1e-6 * mesh->GetLength());
  }
}

// A sheet with a sharp corner: a triangle of 3 degrees at its tip, subdivided (4,096
// triangles). The planes through the boundary edges that hold an open boundary within epsilon
// are almost parallel at the tip and barely see it pulled back: at 1% the level lost 15% of
// the sheet's length there. A boundary tip (under 30 degrees) draws its cluster's
// representative and bounds its error, so both levels keep the sheet exactly.
void TestSharpBoundaryTip()
{
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(0.0, 0.0, 0.0);
  points->InsertNextPoint(1.0, 0.0, 0.0);
  points->InsertNextPoint(1.0, std::tan(vtkMath::RadiansFromDegrees(3.0)), 0.0);
  vtkNew<vtkCellArray> cells;
  const vtkIdType corners[3] = { 0, 1, 2 };
  cells->InsertNextCell(3, corners);
  vtkNew<vtkPolyData> sheet;
  sheet->SetPoints(points);
  sheet->SetPolys(cells);
  vtkNew<vtkLinearSubdivisionFilter> subdivide;
  subdivide->SetInputData(sheet);
  subdivide->SetNumberOfSubdivisions(6);
  subdivide->Update();
  vtkPolyData* mesh = subdivide->GetOutput();
  MESHLOD_REQUIRE_EQ(mesh->GetNumberOfPolys(), 4096);
  vtkNew<vtkVertexClusterOctree> filter;
  vtkMultiBlockDataSet* h = AtTenthAndHundredth(filter, mesh);
  MESHLOD_REQUIRE_EQ(h->GetNumberOfBlocks(), 3u);
  for (unsigned int i = 1; i < 3; ++i)
  {
    const SurfaceDistance d = MeasureSurfaceDistance(mesh, Level(h, i));
    std::cerr << "  3-degree sheet, level " << i << ": " << Level(h, i)->GetNumberOfPolys()
              << " triangles, Hausdorff " << d.HausdorffPercent() << "%\n";
    MESHLOD_CHECK_LE(d.HausdorffPercent(), 1e-4);
    MESHLOD_CHECK_LE(Level(h, i)->GetBounds()[0], 1e-9); // the tip
  }
}

void TestBoundaries()
{
  // A wavy open sheet: its boundary curves in z.
  vtkSmartPointer<vtkPolyData> wave = testing::MakeGrid(60, 60);
  for (vtkIdType p = 0; p < wave->GetNumberOfPoints(); ++p)
  {
    double x[3];
    wave->GetPoint(p, x);
    x[2] = 4.0 * std::sin(0.15 * x[0]) * std::cos(0.1 * x[1]);
    wave->GetPoints()->SetPoint(p, x);
  }
  TestOpenBoundary(wave, "wave");
  // A cap of an isosurface sphere: a round boundary.
  vtkSmartPointer<vtkPolyData> sphere = testing::MakeIsosurface(testing::Field::Sphere, 50);
  std::vector<double> points;
  std::vector<long long> cap;
  for (vtkIdType p = 0; p < sphere->GetNumberOfPoints(); ++p)
  {
    const double* x = sphere->GetPoint(p);
    points.insert(points.end(), x, x + 3);
  }
  for (const Triangle& t : Triangles(sphere))
  {
    double z = 0.0;
    for (const vtkIdType v : t)
    {
      z += sphere->GetPoint(v)[2];
    }
    if (z > 0.6)
    {
      cap.insert(cap.end(), { t[0], t[1], t[2] });
    }
  }
  TestOpenBoundary(testing::MakePolyData(points, cap), "cap");
}

//------------------------------------------------------------------------------
// Non-manifold vertices are locked: two spheres sharing one vertex keep it, in place, on every
// level.
void TestNonManifold()
{
  // Sphere A, and sphere B its mirror image through the plane x = x_m of A's rightmost vertex m:
  // they touch at m only, which becomes one vertex with two fans.
  vtkSmartPointer<vtkPolyData> sphere = testing::MakeIcosphere(3);
  const vtkIdType n = sphere->GetNumberOfPoints();
  vtkIdType m = 0;
  for (vtkIdType p = 1; p < n; ++p)
  {
    m = sphere->GetPoint(p)[0] > sphere->GetPoint(m)[0] ? p : m;
  }
  double p0[3];
  sphere->GetPoint(m, p0);
  vtkSmartPointer<vtkPolyData> twin = testing::MakeTwinTouchingAt(
    sphere, m, m, [&p0](double x[3]) { x[0] = 2.0 * p0[0] - x[0]; }, true);

  vtkNew<vtkVertexClusterOctree> filter;
  filter->SetInputData(twin);
  filter->SetNumberOfLevels(3);
  filter->SetEpsilon(0.01);
  filter->Update();
  vtkMultiBlockDataSet* h = filter->GetHierarchy();
  MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 4u);
  MESHLOD_CHECK_EQ(testing::CountRepeatedPointTriangles(h), 0);
  for (unsigned int i = 1; i < h->GetNumberOfBlocks(); ++i)
  {
    vtkPolyData* level = Level(h, i);
    MESHLOD_CHECK_LT(level->GetNumberOfPolys(), twin->GetNumberOfPolys());
    vtkIdType at = -1;
    for (vtkIdType p = 0; p < level->GetNumberOfPoints(); ++p)
    {
      at = vtkMath::Distance2BetweenPoints(level->GetPoint(p), p0) == 0.0 ? p : at;
    }
    MESHLOD_CHECK_GE(at, 0);
    // Both spheres still meet there: triangles on both sides of x = p0.x use it.
    int left = 0, right = 0;
    for (const Triangle& t : Triangles(level))
    {
      if (t[0] == at || t[1] == at || t[2] == at)
      {
        double c = 0.0;
        for (const vtkIdType v : t)
        {
          c += level->GetPoint(v)[0] / 3.0;
        }
        (c < p0[0] ? left : right) += 1;
      }
    }
    MESHLOD_CHECK_GT(left, 0);
    MESHLOD_CHECK_GT(right, 0);
  }
}

//------------------------------------------------------------------------------
// A rough plane (a grid with height noise of 15% of its edges): clusters would fold it onto
// itself, leaving edges of three or four triangles. Such clusters are refused like those that
// flip triangles: every level stays manifold.
void TestRoughPlane()
{
  vtkSmartPointer<vtkPolyData> grid = testing::MakeGrid(150, 150);
  std::uint32_t state = 12345;
  for (vtkIdType p = 0; p < grid->GetNumberOfPoints(); ++p)
  {
    state = state * 1664525u + 1013904223u; // a fixed pseudo-random sequence
    double x[3];
    grid->GetPoint(p, x);
    x[2] = 0.15 * (static_cast<double>(state >> 8) / 16777216.0 - 0.5);
    grid->GetPoints()->SetPoint(p, x);
  }
  vtkNew<vtkVertexClusterOctree> cluster;
  cluster->SetInputData(grid);
  cluster->SetLevelModeToTargetTriangleCounts();
  cluster->AddTargetTriangleCount(20000);
  cluster->AddTargetTriangleCount(4500);
  cluster->Update();
  vtkMultiBlockDataSet* h = cluster->GetHierarchy();
  MESHLOD_CHECK_GE(h->GetNumberOfBlocks(), 2u);
  for (unsigned int i = 1; i < h->GetNumberOfBlocks(); ++i)
  {
    const testing::MeshReport r = testing::InspectMesh(Level(h, i));
    std::cerr << "rough plane level " << i << ": " << r.Triangles << " triangles, "
              << r.NonManifoldEdges << " non-manifold edges\n";
    MESHLOD_CHECK_LT(r.Triangles, 45000);
    MESHLOD_CHECK_EQ(r.NonManifoldEdges, 0);
    MESHLOD_CHECK_EQ(r.NonManifoldVertices, 0);
    MESHLOD_CHECK_EQ(r.DegenerateTriangles, 0);
    MESHLOD_CHECK_EQ(r.DuplicateTriangles, 0);
  }
}

// A rough terrain: smooth hills plus uniform noise of 3 grid spacings, on an n x n grid.
vtkSmartPointer<vtkPolyData> MakeNoisyTerrain(int n)
{
  vtkSmartPointer<vtkPolyData> grid = testing::MakeGrid(n, n);
  std::uint32_t state = 4;
  for (vtkIdType p = 0; p < grid->GetNumberOfPoints(); ++p)
  {
    state = state * 1664525u + 1013904223u;
    double x[3];
    grid->GetPoint(p, x);
    const double u = x[0] / n, v = x[1] / n;
    x[2] = n * (0.08 * std::sin(6 * u) * std::cos(5 * v) + 0.04 * std::sin(17 * u + 3 * v) +
             0.02 * std::sin(31 * v - 7 * u)) +
      3.0 * (static_cast<double>(state >> 8) / 16777216.0 - 0.5);
    grid->GetPoints()->SetPoint(p, x);
  }
  return grid;
}

// A noisy terrain (waves plus height noise of up to 1.5 edges) cut at an epsilon as large as
// its waves: the first cut folds it almost everywhere, and fixing the folds takes 29 passes.
// With the passes capped at 16 the level kept 3 non-manifold edges (a larger terrain, 40); now
// passes go on, splitting stubborn clusters back into the previous level's points at the end,
// until none is left.
void TestNoisyTerrain()
{
  vtkSmartPointer<vtkPolyData> grid = MakeNoisyTerrain(120);
  vtkNew<vtkVertexClusterOctree> cluster;
  cluster->SetInputData(grid);
  cluster->SetLevelModeToEpsilonList();
  cluster->AddEpsilonValue(0.05);
  cluster->Update();
  vtkMultiBlockDataSet* h = cluster->GetHierarchy();
  MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 2u);
  if (h->GetNumberOfBlocks() == 2)
  {
    const testing::MeshReport r = testing::InspectMesh(Level(h, 1));
    std::cerr << "noisy terrain at epsilon 0.05: " << r.Triangles << " triangles, "
              << r.NonManifoldEdges << " non-manifold edges\n";
    MESHLOD_CHECK_LT(r.Triangles, Level(h, 0)->GetNumberOfPolys() / 2);
    MESHLOD_CHECK_EQ(r.NonManifoldEdges, 0);
    MESHLOD_CHECK_EQ(r.NonManifoldVertices, 0);
    MESHLOD_CHECK_EQ(r.DuplicateTriangles, 0);
  }
}

// Target counts on the rough terrain, where fixing folds keeps many more triangles than asked.
// The second level used to be cut at the octree's roots (2 triangles for a terrain): its first
// trial kept far too many, the corrected aim fell to 1 triangle, and the search preferred the
// smallest difference to the target.
void TestNoisyTerrainCounts()
{
  vtkSmartPointer<vtkPolyData> grid = MakeNoisyTerrain(160);
  const vtkIdType input = grid->GetNumberOfPolys();
  vtkNew<vtkVertexClusterOctree> cluster;
  vtkMultiBlockDataSet* h = AtTenthAndHundredth(cluster, grid);
  MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 3u);
  MESHLOD_CHECK(CheckHierarchyLayout(h, true).empty());
  for (unsigned int i = 1; i < h->GetNumberOfBlocks(); ++i)
  {
    const testing::MeshReport r = testing::InspectMesh(Level(h, i));
    const meshlod::SurfaceDistance d = meshlod::MeasureSurfaceDistance(grid, Level(h, i));
    std::cerr << "noisy terrain, target " << input / (i == 1 ? 10 : 100) << ": " << r.Triangles
              << " triangles, Hausdorff " << d.HausdorffPercent() << "%\n";
    // Measured: 6620 and 639 triangles, Hausdorff 1.4% and 16.0% (the 1% level's estimated error
    // is 26% of the diagonal: the noise is as large as an edge). Before the flip test compared
    // with the clusters' surface normals and islands joined their neighbours' cells: 9118 and
    // 4838 triangles; before that the second level had 2 triangles (18.8%).
    const vtkIdType target = input / (i == 1 ? 10 : 100);
    MESHLOD_CHECK_GT(r.Triangles, target / 2);
    MESHLOD_CHECK_LT(r.Triangles, 2 * target);
    MESHLOD_CHECK_LT(r.Triangles, Level(h, i - 1)->GetNumberOfPolys());
    MESHLOD_CHECK_LT(d.HausdorffPercent(), i == 1 ? 5.0 : 20.0);
    MESHLOD_CHECK_EQ(r.NonManifoldEdges, 0);
    MESHLOD_CHECK_EQ(r.NonManifoldVertices, 0);
    MESHLOD_CHECK_EQ(r.DuplicateTriangles, 0);
  }
  // Two triangles folded onto each other used to lose one of them as a duplicate: a
  // non-manifold vertex, and fine triangles whose MorphTargetId image was the kept one,
  // opposite in orientation (6 such violations here). Such clusters are now split again.
  MESHLOD_CHECK_EQ(testing::CountCorrespondenceViolations(h), 0);
}

// A fan of 50,000 triangles around one point: levels at their counts, valid and nested. (Input
// validation used to scan the centre's triangles once per triangle: quadratic in the valence.)
// A sphere with radial noise of up to two thirds of an edge, at target counts: the first level's fold
// refusals leave nothing mergeable below the octree's root for the second, whose trials keep no
// triangle; the hierarchy used to stop at level 1 with a warning. The search then runs again
// without those refusals.
void TestNoisySphereCounts()
{
  vtkNew<vtkSphereSource> source;
  source->SetThetaResolution(200);
  source->SetPhiResolution(200);
  source->Update();
  vtkNew<vtkPolyData> sphere;
  sphere->DeepCopy(source->GetOutput());
  sphere->GetPointData()->Initialize();
  testing::PerturbRadially(sphere, 0.04, 3);
  const vtkIdType input = sphere->GetNumberOfPolys();
  vtkNew<vtkVertexClusterOctree> cluster;
  vtkMultiBlockDataSet* h = AtTenthAndHundredth(cluster, sphere);
  MESHLOD_REQUIRE_EQ(h->GetNumberOfBlocks(), 3u);
  const testing::MeshReport r = testing::InspectMesh(Level(h, 2));
  const meshlod::SurfaceDistance d = meshlod::MeasureSurfaceDistance(sphere, Level(h, 2));
  std::cerr << "noisy sphere, target " << input / 100 << ": " << r.Triangles
            << " triangles, Hausdorff " << d.HausdorffPercent() << "%\n";
  MESHLOD_CHECK_LT(r.Triangles, Level(h, 1)->GetNumberOfPolys());
  MESHLOD_CHECK_EQ(r.NonManifoldEdges, 0);
  // Measured: 914 triangles (asked 792), Hausdorff 2.0%; 8300 before the flip test compared
  // with the clusters' surface normals and islands joined their neighbours' cells (each alone:
  // 1466 and 3508). Both levels had a three-edge hole where two triangles folded onto each
  // other lost one of them as a duplicate.
  MESHLOD_CHECK_LT(r.Triangles, 3 * (input / 100) / 2);
  MESHLOD_CHECK_LT(d.HausdorffPercent(), 4.0);
  MESHLOD_CHECK_EQ(testing::InspectMesh(Level(h, 1)).BoundaryEdges, 0);
  MESHLOD_CHECK_EQ(r.BoundaryEdges, 0);
  MESHLOD_CHECK_EQ(r.NonManifoldVertices, 0);
  MESHLOD_CHECK_EQ(testing::CountCorrespondenceViolations(h), 0);
}

// A thin tube wound into a helix (a capped tube: a sphere's topology), at target counts. Where a
// cell held the tube's whole cross-section its triangles degenerated: the coarse level broke
// into 7 capped pieces of tube (20 on a longer helix, 13.6% Hausdorff distance). Every level
// must keep the tube in one closed piece.
void TestThinTube()
{
  vtkNew<vtkPoints> axis;
  vtkNew<vtkCellArray> line;
  const int samples = 800;
  line->InsertNextCell(samples);
  for (int i = 0; i < samples; ++i)
  {
    const double t = 8.0 * vtkMath::Pi() * i / (samples - 1); // four turns
    axis->InsertNextPoint(std::cos(t), std::sin(t), 0.15 * t);
    line->InsertCellPoint(i);
  }
  vtkNew<vtkPolyData> helix;
  helix->SetPoints(axis);
  helix->SetLines(line);
  vtkNew<vtkTubeFilter> tube;
  tube->SetInputData(helix);
  tube->SetRadius(0.05);
  tube->SetNumberOfSides(12);
  tube->CappingOn();
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(tube->GetOutputPort());
  vtkNew<vtkCleanPolyData> clean; // the caps' points coincide with the tube's last rings
  clean->SetInputConnection(triangles->GetOutputPort());
  clean->Update();
  vtkPolyData* mesh = clean->GetOutput();
  MESHLOD_CHECK_EQ(testing::InspectMesh(mesh).EulerCharacteristic, 2);
  vtkNew<vtkVertexClusterOctree> cluster;
  vtkMultiBlockDataSet* h = AtTenthAndHundredth(cluster, mesh);
  MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 3u);
  for (unsigned int i = 1; i < h->GetNumberOfBlocks(); ++i)
  {
    const testing::MeshReport r = testing::InspectMesh(Level(h, i));
    const vtkIdType target = mesh->GetNumberOfPolys() / (i == 1 ? 10 : 100);
    std::cerr << "thin tube, target " << target << ": " << r.Triangles << " triangles, Euler "
              << r.EulerCharacteristic << "\n";
    // Measured: 2306 and 124 triangles (asked 1919 and 191). With islands joining their
    // neighbours' cells the tube pinched instead of breaking, 12 closed pieces joined at
    // vertices (Euler 24), until pinched vertices were split again too.
    MESHLOD_CHECK_LE(std::abs(r.Triangles - target), 2 * target / 5);
    MESHLOD_CHECK_EQ(r.EulerCharacteristic, 2); // one closed piece (7 pieces gave 14)
    MESHLOD_CHECK_EQ(r.BoundaryEdges, 0);
    MESHLOD_CHECK_EQ(r.NonManifoldEdges, 0);
    MESHLOD_CHECK_EQ(r.NonManifoldVertices, 0);
  }
  MESHLOD_CHECK_EQ(testing::CountCorrespondenceViolations(h), 0);
}

void TestHighValenceFan()
{
  vtkSmartPointer<vtkPolyData> fan = testing::MakeFan(50000);
  vtkNew<vtkVertexClusterOctree> cluster;
  cluster->SetInputData(fan);
  cluster->SetLevelModeToTargetTriangleCounts();
  cluster->AddTargetTriangleCount(5000);
  cluster->AddTargetTriangleCount(500);
  cluster->Update();
  vtkMultiBlockDataSet* h = cluster->GetHierarchy();
  MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 3u);
  MESHLOD_CHECK(CheckHierarchyLayout(h, true).empty());
  for (unsigned int i = 1; i < h->GetNumberOfBlocks(); ++i)
  {
    const testing::MeshReport r = testing::InspectMesh(Level(h, i));
    const vtkIdType target = i == 1 ? 5000 : 500;
    MESHLOD_CHECK_LE(std::abs(r.Triangles - target), std::max<vtkIdType>(2, target / 500));
    MESHLOD_CHECK_EQ(r.NonManifoldEdges, 0);
    MESHLOD_CHECK_EQ(r.DegenerateTriangles, 0);
    MESHLOD_CHECK_EQ(r.DuplicateTriangles, 0);
  }
  MESHLOD_CHECK_EQ(testing::CountRepeatedPointTriangles(h), 0);
}
} // namespace

int TestVertexClusterOctreeShapes(int, char*[])
{
  TestFlatFacedSolid();
  TestSinglePrecisionPrism();
  TestFlipFreeRepresentatives();
  TestSheetsAlongCurve();
  TestBoundaries();
  TestSharpBoundaryTip();
  TestNonManifold();
  TestRoughPlane();
  TestNoisyTerrain();
  TestNoisyTerrainCounts();
  TestNoisySphereCounts();
  TestThinTube();
  TestHighValenceFan();
  return meshlod::testing::Result();
}
