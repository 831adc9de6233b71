// vtkTriangleCollapseDecimation on particular shapes: flat grids and faces, a faceted cylinder,
// a parametric seam, high-valence fans, noisy surfaces, holes, non-orientable surfaces, an
// extruded solid and a mesh far from the origin; against vtkQuadricDecimation where the shape
// makes accuracy hard.
#include "vtkLODGeomorph.h"
#include "vtkTriangleCollapseDecimation.h"

#include "MeshLODEventCounter.h"
#include "MeshLODHierarchyChecks.h"
#include "MeshLODSurfaceDistance.h"
#include "MeshLODTestCheck.h"
#include "MeshLODTestHierarchies.h"
#include "MeshLODTestMeshes.h"

#include "vtkAdaptiveSubdivisionFilter.h"
#include "vtkAppendPolyData.h"
#include "vtkCellArray.h"
#include "vtkCleanPolyData.h"
#include "vtkCommand.h"
#include "vtkCubeSource.h"
#include "vtkCylinderSource.h"
#include "vtkLinearExtrusionFilter.h"
#include "vtkLinearSubdivisionFilter.h"
#include "vtkMath.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkParametricBoy.h"
#include "vtkParametricFunctionSource.h"
#include "vtkParametricMobius.h"
#include "vtkParametricTorus.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkQuadricDecimation.h"
#include "vtkSOADataArrayTemplate.h"
#include "vtkSphereSource.h"
#include "vtkTessellatedBoxSource.h"
#include "vtkTestErrorObserver.h"
#include "vtkTriangleFilter.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace
{
using namespace meshlod;
using testing::Level;

// The distances to `input` of `level` and of vtkQuadricDecimation at the same triangle count
// (20,000 samples per surface), printed under `label`.
struct PeerComparison
{
  SurfaceDistance Ours;
  SurfaceDistance Theirs;
  vtkSmartPointer<vtkPolyData> Peer; // vtkQuadricDecimation's output
};
PeerComparison CompareWithQuadricDecimation(
  vtkPolyData* input, vtkPolyData* level, const std::string& label)
{
  vtkNew<vtkQuadricDecimation> peer;
  peer->SetInputData(input);
  peer->SetTargetReduction(
    1.0 - static_cast<double>(level->GetNumberOfPolys()) / input->GetNumberOfPolys());
  peer->Update();
  SurfaceDistanceOptions options;
  options.SamplesPerSurface = 20000;
  const PeerComparison c = { MeasureSurfaceDistance(input, level, options),
    MeasureSurfaceDistance(input, peer->GetOutput(), options), peer->GetOutput() };
  std::cerr << "  " << label << " at " << level->GetNumberOfPolys()
            << " triangles: Hausdorff " << c.Ours.HausdorffPercent() << "%, RMS "
            << c.Ours.RmsPercent() << "% (vtkQuadricDecimation at "
            << peer->GetOutput()->GetNumberOfPolys() << ": " << c.Theirs.HausdorffPercent()
            << "%, " << c.Theirs.RmsPercent() << "%)\n";
  return c;
}

// A flat grid: every collapse costs exactly 0, so only the order between equal costs decides.
// Collapses must spread evenly over the grid rather than pile up around one vertex (measured:
// largest valence 11; 65 when ties went to the lowest triangle id, and on a 150 x 150 grid that
// run was 15 times slower).
void TestFlatGrid()
{
  vtkSmartPointer<vtkPolyData> grid = testing::MakeGrid(60, 60);
  vtkNew<vtkTriangleCollapseDecimation> filter;
  filter->SetInputData(grid);
  filter->SetNumberOfLevels(1);
  filter->SetTargetReduction(0.9);
  filter->ComputeLevelErrorOn();
  filter->Update();
  vtkPolyData* coarse = Level(filter->GetHierarchy(), 1);
  MESHLOD_REQUIRE(coarse != nullptr);
  MESHLOD_CHECK_LE(std::abs(coarse->GetNumberOfPolys() - 720), 2);
  const TriangleMesh mesh = testing::ToTriangleMesh(coarse);
  TriangleTopology topology;
  topology.Build(mesh);
  int largest = 0;
  for (Id v = 0; v < mesh.GetNumberOfPoints(); ++v)
  {
    largest = std::max(largest, topology.Valence(mesh, v));
  }
  std::cerr << "  flat grid at 10%: largest valence " << largest << "\n";
  MESHLOD_CHECK_LE(largest, 14);
  // Still exactly flat, and the square's outline kept (up to the minimiser's regularisation,
  // a relative 1e-6 of the unit grid spacing).
  double bounds[6];
  coarse->GetBounds(bounds);
  MESHLOD_CHECK_EQ(bounds[4], 0.0);
  MESHLOD_CHECK_EQ(bounds[5], 0.0);
  MESHLOD_CHECK_LE(testing::BoundaryDeviation(grid, coarse), 1e-5);
}

// A faceted, capped cylinder (CAD-like: flat facets meeting at 15 degrees and at right angles)
// is exactly representable with 92 triangles. Decimated to 160, the output must stay on the
// input surface: the merged vertices sit where three planes meet, two of them nearly parallel,
// which the regularised minimiser alone misses (measured: 1.5e-6 of the diagonal; 2.5e-8 with
// its refinement, Quadric::MinimizeRegularized).
void TestFacetedCylinder()
{
  vtkNew<vtkCylinderSource> cylinder;
  cylinder->SetResolution(24);
  cylinder->CappingOn();
  cylinder->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  vtkNew<vtkLinearSubdivisionFilter> subdivide;
  subdivide->SetInputData(testing::TriangulateAndClean(cylinder));
  subdivide->SetNumberOfSubdivisions(3);
  subdivide->Update();
  vtkPolyData* input = subdivide->GetOutput();
  MESHLOD_CHECK_EQ(input->GetNumberOfPolys(), 92 * 64);

  // Both methods keep the solid exactly (the curvature method by collapsing the edges along its
  // rims and faces, where a triangle collapse would cut a rim); the curvature method with
  // triangle collapses only (paper 000's operator) cannot.
  SurfaceDistanceOptions options;
  options.SamplesPerSurface = 20000;
  // (The quadric method lands within one triangle of its target; the curvature method does not
  // trade its last collapse for an edge and may end up to 3 below. The last run's lower bound
  // records what the operator changes: lower it if triangle collapses alone ever keep the rims.)
  // The quadric method keeps it with paper 002's placement too: its faces' quadrics are
  // singular (one plane), and the candidates there are on the face.
  const struct
  {
    int Method, Operator, Placement;
    int Landing;
    double MaximumHausdorff, MinimumHausdorff; // fractions of the diagonal
  } runs[] = {
    { vtkTriangleCollapseDecimation::QUADRIC, vtkTriangleCollapseDecimation::TRIANGLES_AND_EDGES,
      vtkTriangleCollapseDecimation::REGULARIZED, 1, 2e-7, 0.0 },
    { vtkTriangleCollapseDecimation::QUADRIC, vtkTriangleCollapseDecimation::TRIANGLES_AND_EDGES,
      vtkTriangleCollapseDecimation::PAPER_CANDIDATES, 1, 2e-7, 0.0 },
    { vtkTriangleCollapseDecimation::CURVATURE,
      vtkTriangleCollapseDecimation::TRIANGLES_AND_EDGES,
      vtkTriangleCollapseDecimation::REGULARIZED, 3, 2e-7, 0.0 },
    { vtkTriangleCollapseDecimation::CURVATURE, vtkTriangleCollapseDecimation::TRIANGLES,
      vtkTriangleCollapseDecimation::REGULARIZED, 3, 1.0, 0.01 },
  };
  for (const auto& run : runs)
  {
    vtkNew<vtkTriangleCollapseDecimation> filter;
    filter->SetInputData(input);
    filter->SetMethod(run.Method);
    filter->SetOperator(run.Operator);
    filter->SetPlacement(run.Placement);
    filter->SetNumberOfLevels(1);
    filter->SetTargetReduction(1.0 - 160.0 / (92 * 64));
    filter->Update();
    vtkPolyData* coarse = Level(filter->GetHierarchy(), 1);
    MESHLOD_REQUIRE(coarse != nullptr);
    MESHLOD_CHECK_LE(coarse->GetNumberOfPolys(), 160);
    MESHLOD_CHECK_LE(160 - coarse->GetNumberOfPolys(), run.Landing);
    const SurfaceDistance distance = MeasureSurfaceDistance(input, coarse, options);
    std::cerr << "  faceted cylinder, " << filter->GetMethodAsString() << ", "
              << filter->GetOperatorAsString() << ", " << filter->GetPlacementAsString()
              << ", at " << coarse->GetNumberOfPolys()
              << " triangles: Hausdorff " << distance.Hausdorff / distance.Diagonal
              << " of the diagonal\n";
    MESHLOD_CHECK_LE(distance.Hausdorff, run.MaximumHausdorff * distance.Diagonal);
    MESHLOD_CHECK_GE(distance.Hausdorff, run.MinimumHausdorff * distance.Diagonal);
  }

  // The curvature method places by its fit, and its crease edges (many here) by the regularised
  // solve: Placement changes nothing.
  const auto curvature = [&](int placement) {
    vtkNew<vtkTriangleCollapseDecimation> filter;
    filter->SetInputData(input);
    filter->SetMethodToCurvature();
    filter->SetPlacement(placement);
    filter->SetNumberOfLevels(2);
    filter->SetTargetReduction(1.0 - 160.0 / (92 * 64));
    filter->Update();
    return vtkSmartPointer<vtkMultiBlockDataSet>(filter->GetHierarchy());
  };
  MESHLOD_CHECK_EQ(testing::CountDifferingLevels(
                     curvature(vtkTriangleCollapseDecimation::REGULARIZED),
                     curvature(vtkTriangleCollapseDecimation::PAPER_CANDIDATES)),
    0);
}

// The smallest sine of a corner of any triangle of a mesh (0 for a triangle without area).
double SmallestCornerSine(vtkPolyData* mesh)
{
  double smallest = 1.0;
  for (const testing::TriangleIds& t : testing::Triangles(mesh))
  {
    double p[3][3];
    for (int k = 0; k < 3; ++k)
    {
      mesh->GetPoint(t[k], p[k]);
    }
    for (int k = 0; k < 3; ++k)
    {
      double a[3], b[3], cross[3];
      vtkMath::Subtract(p[(k + 1) % 3], p[k], a);
      vtkMath::Subtract(p[(k + 2) % 3], p[k], b);
      vtkMath::Cross(a, b, cross);
      const double lengths = vtkMath::Norm(a) * vtkMath::Norm(b);
      smallest = std::min(smallest, lengths > 0.0 ? vtkMath::Norm(cross) / lengths : 0.0);
    }
  }
  return smallest;
}

// A box with flat faces: quadric solves put collapse points exactly on its corners and edges,
// where a point landing on a neighbour or on the line of a ring edge left triangles of zero area
// (7 on the 96-triangle level) and slivers with corners of sine 7e-9. Every level of every
// method and schedule must be a closed manifold sphere without triangles of (nearly) no area.
void TestFlatFacedBox()
{
  vtkNew<vtkTessellatedBoxSource> box;
  box->SetLevel(8);
  box->QuadsOff();
  vtkSmartPointer<vtkPolyData> input = testing::TriangulateAndClean(box);
  MESHLOD_CHECK_EQ(input->GetNumberOfPolys(), 972);
  for (const int method :
    { vtkTriangleCollapseDecimation::QUADRIC, vtkTriangleCollapseDecimation::CURVATURE })
  {
    for (const int schedule :
      { vtkTriangleCollapseDecimation::GREEDY, vtkTriangleCollapseDecimation::INDEPENDENT_SETS })
    {
      vtkNew<vtkTriangleCollapseDecimation> filter;
      filter->SetInputData(input);
      filter->SetMethod(method);
      filter->SetSchedule(schedule);
      filter->SetTargetReduction(0.95);
      filter->Update();
      vtkMultiBlockDataSet* h = filter->GetHierarchy();
      MESHLOD_CHECK_GT(h->GetNumberOfBlocks(), 4u);
      for (unsigned int i = 1; i < h->GetNumberOfBlocks(); ++i)
      {
        const testing::MeshReport r = testing::InspectMesh(Level(h, i));
        MESHLOD_CHECK_EQ(r.DegenerateTriangles, 0);
        MESHLOD_CHECK_EQ(r.NonManifoldEdges, 0);
        MESHLOD_CHECK_EQ(r.BoundaryEdges, 0);
        MESHLOD_CHECK_EQ(r.EulerCharacteristic, 2);
        MESHLOD_CHECK_GE(SmallestCornerSine(Level(h, i)), 1e-6);
      }
    }
  }
}

// Boxes with rectangular faces (not cubes), finely subdivided, down to 12 and 24 triangles with
// both greedy schedules: exact (12 triangles represent a box). Near the end a triangle's
// cheapest edge is often refused while another edge of it collapses at no cost; the triangle
// then waited (parked) with its refused edge's price, and the collapses left moved corners:
// 20% to 39% of the diagonal at 12 and 24 triangles before the other edges were tried.
void TestRectangularBoxes()
{
  const double sizes[][3] = { { 3.0, 1.0, 1.0 }, { 1.0, 0.1, 1.0 }, { 0.8, 0.3, 1.1 } };
  for (const auto& size : sizes)
  {
    vtkNew<vtkCubeSource> cube;
    cube->SetBounds(0.0, size[0], 0.0, size[1], 0.0, size[2]);
    vtkNew<vtkLinearSubdivisionFilter> subdivide;
    subdivide->SetInputData(testing::TriangulateAndClean(cube));
    subdivide->SetNumberOfSubdivisions(4);
    subdivide->Update();
    vtkPolyData* input = subdivide->GetOutput();
    MESHLOD_CHECK_EQ(input->GetNumberOfPolys(), 3072);
    for (const bool partitioned : { true, false })
    {
      vtkNew<vtkTriangleCollapseDecimation> filter;
      filter->SetInputData(input);
      filter->SetPartitionedGreedy(partitioned);
      filter->AddLevelReduction(1.0 - 24.0 / 3072.0);
      filter->AddLevelReduction(1.0 - 12.0 / 3072.0);
      filter->Update();
      vtkMultiBlockDataSet* h = filter->GetHierarchy();
      MESHLOD_REQUIRE_EQ(h->GetNumberOfBlocks(), 3u);
      for (unsigned int i = 1; i <= 2; ++i)
      {
        MESHLOD_CHECK_EQ(Level(h, i)->GetNumberOfPolys(), (i == 1 ? 24 : 12));
        const SurfaceDistance d = MeasureSurfaceDistance(input, Level(h, i));
        std::cerr << "  box " << size[0] << " x " << size[1] << " x " << size[2]
                  << (partitioned ? "" : ", strict greedy") << ", "
                  << Level(h, i)->GetNumberOfPolys()
                  << " triangles: Hausdorff " << d.HausdorffPercent() << "%\n";
        MESHLOD_CHECK_LE(d.Hausdorff, 1e-6 * d.Diagonal);
      }
    }
  }
}

// VTK's parametric torus closes its seam with points that differ from their twins by rounding
// (about 1e-15), joined by zero-area triangles: as given, the seam is a line of non-manifold
// edges. Validation stitches it (points on boundary or non-manifold edges that coincide up to
// rounding), so the levels are closed manifold tori and the seam does not lock collapses
// (measured before the stitching: the 1% level stopped at 2418 of 1788 triangles with a
// Hausdorff distance of 11% of the diagonal).
void TestParametricSeam()
{
  vtkNew<vtkParametricTorus> torus;
  vtkNew<vtkParametricFunctionSource> source;
  source->SetParametricFunction(torus);
  source->SetUResolution(80);
  source->SetVResolution(80);
  vtkSmartPointer<vtkPolyData> input = testing::TriangulateAndClean(source);
  MESHLOD_CHECK_GT(testing::InspectMesh(input).NonManifoldEdges, 0); // the seam, as given

  vtkNew<vtkTriangleCollapseDecimation> filter;
  filter->SetInputData(input);
  filter->SetNumberOfLevels(4);
  filter->SetTargetReduction(0.99);
  filter->Update();
  vtkMultiBlockDataSet* h = filter->GetHierarchy();
  MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 5u);
  for (unsigned int i = 0; i < h->GetNumberOfBlocks(); ++i)
  {
    const testing::MeshReport report = testing::InspectMesh(Level(h, i));
    MESHLOD_CHECK_EQ(report.NonManifoldEdges, 0);
    MESHLOD_CHECK_EQ(report.BoundaryEdges, 0);
    MESHLOD_CHECK_EQ(report.EulerCharacteristic, 0);
  }
  vtkPolyData* coarse = h->GetNumberOfBlocks() == 5 ? Level(h, 4) : nullptr;
  if (!coarse)
  {
    return;
  }
  MESHLOD_CHECK_LE(coarse->GetNumberOfPolys(), Level(h, 0)->GetNumberOfPolys() / 100 + 1);
  const PeerComparison c = CompareWithQuadricDecimation(input, coarse, "parametric torus");
  MESHLOD_CHECK_LE(c.Ours.Hausdorff, 1.5 * c.Theirs.Hausdorff);
}

// A fan reduced to 10% and 1% in two levels: both on target, valid, still a disk, the open rim
// kept.
void CheckFanLevels(vtkPolyData* fan, int method, bool weight)
{
  vtkNew<vtkTriangleCollapseDecimation> filter;
  filter->SetInputData(fan);
  filter->SetMethod(method);
  if (weight)
  {
    filter->SetCurvatureCostToWeight();
  }
  filter->SetNumberOfLevels(2);
  filter->SetTargetReduction(0.99);
  filter->Update();
  vtkMultiBlockDataSet* h = filter->GetHierarchy();
  MESHLOD_REQUIRE_EQ(h->GetNumberOfBlocks(), 3u);
  const vtkIdType triangles = fan->GetNumberOfPolys();
  for (unsigned int i = 1; i < 3; ++i)
  {
    const vtkIdType target = triangles / (i == 1 ? 10 : 100);
    MESHLOD_CHECK_LE(Level(h, i)->GetNumberOfPolys(), target);
    MESHLOD_CHECK_GE(Level(h, i)->GetNumberOfPolys(), target - 2);
    const testing::MeshReport report = testing::InspectMesh(Level(h, i));
    MESHLOD_CHECK_EQ(report.NonManifoldEdges, 0);
    MESHLOD_CHECK_EQ(report.DegenerateTriangles, 0);
    MESHLOD_CHECK_EQ(report.EulerCharacteristic, 1); // still a disk
  }
  // (Not with paper 000's weight, which does not price the boundary: at 19 triangles a rim
  // point of the fan of 2,000, of radius 1, lies 0.98 inside, with or without the stale
  // marking.)
  if (!weight)
  {
    MESHLOD_CHECK_LE(testing::BoundaryDeviation(fan, Level(h, 2)), 0.01);
  }
}

// A fan of 50,000 triangles around one point (a triangulated polygon, a cylinder's cap), with
// both methods: every level valid and on target, the open rim kept. (Input validation used to
// scan the centre's 50,000 triangles for each of them: the run took 3.4 s here instead of
// 0.2 s, and 45 s for a fan of 200,000. The curvature method's fits read every triangle of the
// fan and re-fitted them all after every collapse next to it: 9.5 s for a fan of 1,000
// triangles, 88 s for 2,000, days for this one; see FanTriangleLimit.)
void TestHighValenceFan()
{
  vtkSmartPointer<vtkPolyData> fan = testing::MakeFan(50000);
  CheckFanLevels(fan, vtkTriangleCollapseDecimation::QUADRIC, false);
  CheckFanLevels(fan, vtkTriangleCollapseDecimation::CURVATURE, false);
  // Paper 000's weight: each collapse at the centre moves it, and the fan's triangles around it
  // are marked stale rather than re-fitted at once (Collapser::DefersAroundHub; a fan of 2,000
  // took 9 s, now 2.2 s).
  CheckFanLevels(testing::MakeFan(2000), vtkTriangleCollapseDecimation::CURVATURE, true);
}

// A flat fan of 16,000 triangles inside a ring, so that its centre and rim are interior: a
// collapse that moves the centre into its fan folds it and is refused, and every move of the
// centre changes every triangle of the fan. (Each such move had all of them re-weighed and
// re-checked against all of the fan: 4.8 s, and 36 s for a fan of 20,000; before that, when
// each lookup of a solved edge scanned the fan and each refused check sorted its link, two
// minutes. Now a fan triangle collapses by its edge away from the centre, which stays put while
// more than FanTriangleLimit triangles meet there, see TestTriangleCollapseCostWeights: 0.4 s.)
// Every level on target, flat, valid.
void TestFlatFanInRing()
{
  vtkSmartPointer<vtkPolyData> disc = testing::MakeFlatFanInRing(16000);
  vtkNew<vtkTriangleCollapseDecimation> filter;
  filter->SetInputData(disc);
  filter->SetNumberOfLevels(2);
  filter->SetTargetReduction(0.99);
  filter->Update();
  vtkMultiBlockDataSet* h = filter->GetHierarchy();
  MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 3u);
  for (unsigned int i = 1; i < h->GetNumberOfBlocks(); ++i)
  {
    vtkPolyData* level = Level(h, i);
    const vtkIdType target = i == 1 ? 4800 : 480;
    MESHLOD_CHECK_LE(level->GetNumberOfPolys(), target);
    MESHLOD_CHECK_GE(level->GetNumberOfPolys(), target - 1);
    const testing::MeshReport report = testing::InspectMesh(level);
    MESHLOD_CHECK_EQ(report.NonManifoldEdges, 0);
    MESHLOD_CHECK_EQ(report.DegenerateTriangles, 0);
    MESHLOD_CHECK(report.ConsistentlyOriented);
    MESHLOD_CHECK_EQ(report.EulerCharacteristic, 1);
    double bounds[6];
    level->GetBounds(bounds);
    MESHLOD_CHECK(bounds[4] == 0.0 && bounds[5] == 0.0);
  }
  MESHLOD_CHECK_LE(testing::BoundaryDeviation(disc, Level(h, 2)), 0.01);
}

// The same with the IndependentSets schedule, which makes one collapse per pass around the
// centre, and with the TRIANGLES operator, whose collapses the fan mostly refuses: every level
// valid, the default operator's on target. (Refused triangles waiting in the fan were re-checked
// against all of it, and every pass sorted its whole pool of candidates: 5-9 s for the fan of
// 3,000 with the TRIANGLES operator, 22 s for one of 30,000 with the default one.)
void TestHighValenceFanIndependentSets()
{
  vtkSmartPointer<vtkPolyData> fan = testing::MakeFan(3000);
  for (const bool curvature : { false, true })
  {
    for (const int op : { vtkTriangleCollapseDecimation::TRIANGLES_AND_EDGES,
           vtkTriangleCollapseDecimation::TRIANGLES })
    {
      vtkNew<vtkTriangleCollapseDecimation> filter;
      filter->SetInputData(fan);
      filter->SetMethod(curvature ? vtkTriangleCollapseDecimation::CURVATURE
                                  : vtkTriangleCollapseDecimation::QUADRIC);
      filter->SetScheduleToIndependentSets();
      filter->SetOperator(op);
      filter->SetNumberOfLevels(2);
      filter->SetTargetReduction(0.9);
      filter->Update();
      vtkMultiBlockDataSet* h = filter->GetHierarchy();
      const unsigned int levels = h->GetNumberOfBlocks();
      MESHLOD_CHECK_GE(levels, 2u);
      for (unsigned int i = 1; i < levels; ++i)
      {
        const testing::MeshReport report = testing::InspectMesh(Level(h, i));
        MESHLOD_CHECK_EQ(report.NonManifoldEdges, 0);
        MESHLOD_CHECK_EQ(report.DegenerateTriangles, 0);
        MESHLOD_CHECK_EQ(report.EulerCharacteristic, 1);
        MESHLOD_CHECK_LT(Level(h, i)->GetNumberOfPolys(), Level(h, i - 1)->GetNumberOfPolys());
      }
      if (op == vtkTriangleCollapseDecimation::TRIANGLES_AND_EDGES)
      {
        MESHLOD_CHECK_EQ(levels, 3u);
        if (levels == 3)
        {
          MESHLOD_CHECK_LE(Level(h, 2)->GetNumberOfPolys(), 300);
          MESHLOD_CHECK_GE(Level(h, 2)->GetNumberOfPolys(), 298);
          MESHLOD_CHECK_LE(testing::BoundaryDeviation(fan, Level(h, 2)), 0.01);
        }
      }
    }
  }
}

// IndependentSets with the TRIANGLES operator on a UV sphere of long thin triangles (theta
// resolution 300, phi 20): most triangle collapses are refused, the few candidates left crowd
// together and each pass removed a tenth of a triangle or so. Passes that stall hand the level
// to the greedy loop: every level on target and valid, in about 2,500 passes (each pass reports
// progress) where there were 20,000 (on a sphere of 116,000 such triangles the run had not ended
// after five minutes).
void TestIndependentSetsStall()
{
  vtkNew<vtkSphereSource> source;
  source->SetThetaResolution(300);
  source->SetPhiResolution(20);
  source->Update();
  vtkNew<vtkTriangleCollapseDecimation> filter;
  filter->SetInputConnection(source->GetOutputPort());
  filter->SetScheduleToIndependentSets();
  filter->SetOperatorToTriangles();
  filter->SetNumberOfLevels(3);
  filter->SetTargetReduction(0.9);
  const testing::EventCounter reports(filter, vtkCommand::ProgressEvent);
  filter->Update();
  vtkMultiBlockDataSet* h = filter->GetHierarchy();
  MESHLOD_REQUIRE_EQ(h->GetNumberOfBlocks(), 4u);
  const vtkIdType input = Level(h, 0)->GetNumberOfPolys();
  MESHLOD_CHECK_EQ(input, 10800);
  for (unsigned int i = 1; i < 4; ++i)
  {
    const testing::MeshReport report = testing::InspectMesh(Level(h, i));
    MESHLOD_CHECK_EQ(report.NonManifoldEdges, 0);
    MESHLOD_CHECK_EQ(report.BoundaryEdges, 0);
    MESHLOD_CHECK_EQ(report.DegenerateTriangles, 0);
    MESHLOD_CHECK_EQ(report.EulerCharacteristic, 2);
  }
  MESHLOD_CHECK_LE(Level(h, 3)->GetNumberOfPolys(), 1080);
  MESHLOD_CHECK_GE(Level(h, 3)->GetNumberOfPolys(), 1070);
  MESHLOD_CHECK_LT(reports.Count, 5000);
}

// A sphere of 19,600 triangles with uniform radial noise of `amplitude` (relative to the
// radius): every level within 2x vtkQuadricDecimation's errors at the same count, the last at
// its target.
vtkSmartPointer<vtkPolyData> NoisySphere(double amplitude)
{
  vtkNew<vtkSphereSource> source;
  source->SetThetaResolution(100);
  source->SetPhiResolution(100);
  vtkNew<vtkCleanPolyData> clean; // renumbers the points: the noise below depends on it
  clean->SetInputConnection(source->GetOutputPort());
  clean->Update();
  auto sphere = vtkSmartPointer<vtkPolyData>::New();
  sphere->DeepCopy(clean->GetOutput());
  sphere->GetPointData()->Initialize();
  testing::PerturbRadially(sphere, amplitude, 3);
  return sphere;
}

void CheckNoisySphere(double amplitude)
{
  vtkSmartPointer<vtkPolyData> sphere = NoisySphere(amplitude);
  const vtkIdType triangles = sphere->GetNumberOfPolys();
  vtkNew<vtkTriangleCollapseDecimation> filter;
  filter->SetInputData(sphere);
  filter->AddLevelReduction(0.9);
  filter->AddLevelReduction(0.98);
  filter->AddLevelReduction(0.99);
  filter->Update();
  vtkMultiBlockDataSet* h = filter->GetHierarchy();
  MESHLOD_REQUIRE_EQ(h->GetNumberOfBlocks(), 4u);
  MESHLOD_CHECK_LE(Level(h, 3)->GetNumberOfPolys(), triangles / 100 + 3);
  for (unsigned int i = 1; i < 4; ++i)
  {
    vtkPolyData* level = Level(h, i);
    const PeerComparison c = CompareWithQuadricDecimation(
      sphere, level, "noisy sphere (" + std::to_string(amplitude) + ")");
    // At a few hundred triangles of a noisy surface both filters' errors vary by tens of
    // percent with the noise; the bound catches a run that stops collapsing where it should.
    MESHLOD_CHECK_LE(c.Ours.Rms, 2.0 * c.Theirs.Rms);
    MESHLOD_CHECK_LE(c.Ours.Hausdorff, 2.0 * c.Theirs.Hausdorff);
    MESHLOD_CHECK_EQ(testing::InspectMesh(level).NonManifoldEdges, 0);
  }
}

// A scan-like input: a UV sphere (100 x 100, 19,600 triangles) with its radii perturbed by up
// to 4%, more than an edge near the poles. Its triangles' normals scatter widely, and the
// collapses that smooth the noise turn them far from their own normal but towards the surface:
// with a bound of 60 degrees measured against the old normal alone, the run stopped short of
// the 1% level. (At 60 degrees with the new exception for turns towards the
// input surface it still does: the default of 90 is needed too.)
void TestNoisySurface()
{
  CheckNoisySphere(0.08);
  // Radii perturbed by up to 10%, about 1.6 edges: many input triangles face inwards. Refusing every collapse
  // that left one facing away stopped this sphere short of its 2% level (on 79,200 triangles
  // with 2% noise, at 3.3% with a last level whose few huge triangles cut caps off: Hausdorff
  // 17% against vtkQuadricDecimation's 2.2%). Now: RMS 0.60%, 1.19%, 1.81% against 0.59%,
  // 1.21%, 1.86%.
  CheckNoisySphere(0.2);
}

// Hole rims at the coarse levels keep about as many boundary edges as vtkQuadricDecimation
// keeps at the same count (its boundary planes weigh the same per unit length), and the
// distances stay close to its. Measured at 7,199 and 1,438 triangles: 549 and 510 boundary
// edges (vtkQuadricDecimation 548 and 510), Hausdorff 1.00x and 0.98x its. With the weight
// proportional to the input's edge length (BoundaryWeight 10 times its square, the default
// before), the rims kept 533 and 442 (0.87x) and the Hausdorff distance at 1,438 was 1.26x.
void TestSurfaceWithHoles()
{
  vtkSmartPointer<vtkPolyData> input = testing::MakeBumpySphereWithHoles(6);
  vtkNew<vtkTriangleCollapseDecimation> filter;
  filter->SetInputData(input);
  filter->AddLevelReduction(0.9);
  filter->AddLevelReduction(0.98);
  filter->Update();
  vtkMultiBlockDataSet* h = filter->GetHierarchy();
  MESHLOD_REQUIRE_EQ(h->GetNumberOfBlocks(), 3u);
  const testing::MeshReport fine = testing::InspectMesh(input);
  MESHLOD_CHECK_GT(fine.BoundaryEdges, 0);
  for (unsigned int i = 1; i < 3; ++i)
  {
    vtkPolyData* level = Level(h, i);
    const PeerComparison c = CompareWithQuadricDecimation(input, level, "sphere with holes");
    const testing::MeshReport ours = testing::InspectMesh(level);
    const testing::MeshReport theirs = testing::InspectMesh(c.Peer);
    std::cerr << "    boundary edges: " << ours.BoundaryEdges << " (vtkQuadricDecimation "
              << theirs.BoundaryEdges << ", input " << fine.BoundaryEdges << ")\n";
    MESHLOD_CHECK_EQ(ours.EulerCharacteristic, fine.EulerCharacteristic);
    MESHLOD_CHECK_GE(ours.BoundaryEdges, 0.93 * theirs.BoundaryEdges);
    MESHLOD_CHECK_LE(ours.BoundaryEdges, 1.1 * theirs.BoundaryEdges);
    MESHLOD_CHECK_LE(c.Ours.Hausdorff, 1.15 * c.Theirs.Hausdorff);
    MESHLOD_CHECK_LE(c.Ours.Rms, 1.1 * c.Theirs.Rms);
  }
}

// BoundaryWeight's largest value holds a terrain's boundary about as well as the default: the
// range ends at 10, where the surface planes still count in the placement. (Up to 1e6 before:
// there the boundary planes swamped them, collapse points slid towards their vertices'
// centroid, and at 1e6 the coarsest level of this terrain was 3.1 times as far from the input
// as with the default, two thirds as far as with boundaries free to move; now 1.3 times.)
void TestLargestBoundaryWeight()
{
  vtkSmartPointer<vtkPolyData> input = testing::MakeTerrain(50);
  auto coarsestDistance = [&](double weight)
  {
    vtkNew<vtkTriangleCollapseDecimation> filter;
    filter->SetInputData(input);
    filter->SetBoundaryWeight(weight);
    filter->Update();
    vtkMultiBlockDataSet* h = filter->GetHierarchy();
    vtkPolyData* coarsest = Level(h, h->GetNumberOfBlocks() - 1);
    MESHLOD_CHECK_LE(coarsest->GetNumberOfPolys(), input->GetNumberOfPolys() / 100 + 3);
    return MeasureSurfaceDistance(input, coarsest).Hausdorff;
  };
  vtkNew<vtkTriangleCollapseDecimation> clamped;
  clamped->SetBoundaryWeight(1.0e6);
  MESHLOD_CHECK_EQ(clamped->GetBoundaryWeight(), 10.0);
  const double byDefault = coarsestDistance(0.3);
  const double largest = coarsestDistance(1.0e6);
  const double free = coarsestDistance(0.0);
  std::cerr << "  terrain's coarsest level, Hausdorff distance: BoundaryWeight 0.3 " << byDefault
            << ", the largest " << largest << ", 0 " << free << "\n";
  MESHLOD_CHECK_LE(largest, 2.0 * byDefault);
  MESHLOD_CHECK_LE(2.0 * largest, free);
}

// The curvature method's triangle collapses must also pass paper 000's star-shape test, which
// on a noisy surface refuses most of them once triangles are large: on the sphere with radii
// perturbed by up to 8% it stopped at 5,144 of 19,600 triangles, asked for 196. A run that
// would stop short now relaxes the test once (a ring triangle already on the wrong side of the
// plane may stay there) and goes on: this sphere reaches 1% at 2.1x vtkQuadricDecimation's
// Hausdorff and 1.6x its RMS distance with paper 000's weight. Runs that reach their targets
// under the strict test are unchanged. Ranked by the fit's deviation (the default) the run
// does worse on this rough input, 4.0x and 4.6x: between 3,500 and 2,000 triangles it makes
// long triangles that cut across the sphere near its poles (valence 100 in the input), which
// the fit to noisy points does not price (without noise it is far better than the weight:
// TestSmoothSphereCurvature).
// The curvature method's 1% level of `sphere` with the given ranking, against
// vtkQuadricDecimation at the same count; the level is checked to reach its count.
PeerComparison CurvatureAtOnePercent(vtkPolyData* sphere, int ranking, const std::string& name)
{
  vtkNew<vtkTriangleCollapseDecimation> filter;
  filter->SetInputData(sphere);
  filter->SetMethodToCurvature();
  filter->SetCurvatureCost(ranking);
  filter->SetTargetReduction(0.99);
  filter->Update();
  vtkMultiBlockDataSet* h = filter->GetHierarchy();
  vtkPolyData* coarse = Level(h, h->GetNumberOfBlocks() - 1);
  MESHLOD_CHECK_LE(coarse->GetNumberOfPolys(), sphere->GetNumberOfPolys() / 100 + 3);
  const testing::MeshReport report = testing::InspectMesh(coarse);
  MESHLOD_CHECK_EQ(report.NonManifoldEdges, 0);
  MESHLOD_CHECK_EQ(report.EulerCharacteristic, 2);
  return CompareWithQuadricDecimation(sphere, coarse,
    name + ", curvature method, ranked by " + filter->GetCurvatureCostAsString());
}

void TestNoisySurfaceCurvature(int ranking, double maxHausdorffRatio, double maxRmsRatio)
{
  const double amplitude = 0.08;
  const PeerComparison c = CurvatureAtOnePercent(
    NoisySphere(amplitude), ranking, "noisy sphere (" + std::to_string(amplitude) + ")");
  MESHLOD_CHECK_LE(c.Ours.Hausdorff, maxHausdorffRatio * c.Theirs.Hausdorff);
  MESHLOD_CHECK_LE(c.Ours.Rms, maxRmsRatio * c.Theirs.Rms);
}

// The same UV sphere without noise, at 1%: ranked by the fit's deviation the curvature method
// is within 1.5x of vtkQuadricDecimation's distances (measured: 1.14x and 1.06x), far below
// paper 000's weight (4.0x and 2.3x).
void TestSmoothSphereCurvature()
{
  vtkSmartPointer<vtkPolyData> sphere = NoisySphere(0.0);
  const PeerComparison deviation =
    CurvatureAtOnePercent(sphere, vtkTriangleCollapseDecimation::FIT_DEVIATION, "smooth sphere");
  const PeerComparison weight =
    CurvatureAtOnePercent(sphere, vtkTriangleCollapseDecimation::WEIGHT, "smooth sphere");
  MESHLOD_CHECK_LE(deviation.Ours.Hausdorff, 1.5 * deviation.Theirs.Hausdorff);
  MESHLOD_CHECK_LE(deviation.Ours.Rms, 1.5 * deviation.Theirs.Rms);
  MESHLOD_CHECK_LE(deviation.Ours.Hausdorff, 0.6 * weight.Ours.Hausdorff);
  MESHLOD_CHECK_LE(deviation.Ours.Rms, 0.6 * weight.Ours.Rms);
}

// Non-orientable surfaces (a Moebius strip, Boy's surface) cannot be oriented consistently:
// somewhere two neighbouring triangles disagree on the direction of their shared edge. The link
// test of a collapse used directed edges and refused every collapse along that seam: at 1% of
// about 20,000 triangles the Moebius strip stopped at 202 triangles with a Hausdorff distance of
// 17.9% of the diagonal and an RMS distance of 5.3% (vtkQuadricDecimation: 0.53% and 0.10%),
// Boy's surface at 214 with 23.4% and 5.2% (1.54% and 0.30%). Now: 1.16x and 1.00x, 0.82x and
// 1.05x vtkQuadricDecimation's.
// The curvature method's triangle collapses also met paper 000's star-shape test, which judged
// a ring triangle across the seam by its orientation: the Moebius strip stopped at 277
// triangles (21x vtkQuadricDecimation's Hausdorff and 24x its RMS distance), Boy's surface at
// 452 (18x, 11x). On such a mesh the test now asks that no new triangle changes side of the
// collapsing triangle's plane: both reach 1%, ranked by the fit's deviation (the default) at
// 1.4x and 2.0x, and 0.9x and 1.2x (with paper 000's weight at 4.8x and 5.9x, and 3.3x and
// 3.2x, its usual distance from vtkQuadricDecimation on isosurfaces).
template <typename Surface>
void CheckNonOrientable(const char* name, bool curvature)
{
  vtkNew<Surface> surface;
  vtkNew<vtkParametricFunctionSource> source;
  source->SetParametricFunction(surface);
  source->SetUResolution(100);
  source->SetVResolution(100);
  source->GenerateTextureCoordinatesOff();
  // The seam's two sides coincide up to rounding only, and their normals differ: with normals
  // the filter would keep them apart as an attribute seam.
  source->GenerateNormalsOff();
  source->SetScalarModeToNone();
  vtkSmartPointer<vtkPolyData> input = testing::TriangulateAndClean(source);
  const vtkIdType count = input->GetNumberOfPolys();

  vtkNew<vtkTriangleCollapseDecimation> filter;
  filter->SetInputData(input);
  filter->SetTargetReduction(0.99);
  if (curvature)
  {
    filter->SetMethodToCurvature();
  }
  filter->Update();
  vtkMultiBlockDataSet* h = filter->GetHierarchy();
  // Level 0, the validated input: stitched (manifold) and not orientable.
  const testing::MeshReport fine = testing::InspectMesh(Level(h, 0));
  MESHLOD_CHECK_EQ(fine.NonManifoldEdges, 0);
  MESHLOD_CHECK(!fine.ConsistentlyOriented);
  vtkPolyData* coarse = Level(h, h->GetNumberOfBlocks() - 1);
  MESHLOD_CHECK_LE(coarse->GetNumberOfPolys(), count / 100 + 3);
  const testing::MeshReport report = testing::InspectMesh(coarse);
  MESHLOD_CHECK_EQ(report.NonManifoldEdges, 0);
  MESHLOD_CHECK_EQ(report.NonManifoldVertices, 0);
  MESHLOD_CHECK_EQ(report.EulerCharacteristic, fine.EulerCharacteristic);
  const std::string label = std::string(name) + (curvature ? ", curvature method" : "");
  if (!curvature)
  {
    // Exact counts across the levels: the schedule's one-fan test followed the link's
    // direction, which across the seam is not consistent, so that the steps after a seam
    // vertex's merge could not be stopped at (here Boy's surface missed counts by up to 329
    // triangles; at the start of this stop, before collapses could wait for their neighbours,
    // the Moebius strip by 3,728 and Boy's surface by 8,013).
    vtkNew<vtkLODGeomorph> geomorph;
    geomorph->SetInputData(h);
    const vtkIdType finest = Level(h, 0)->GetNumberOfPolys();
    vtkIdType worst = 0;
    for (int k = 0; k <= 40; ++k)
    {
      const vtkIdType asked = coarse->GetNumberOfPolys() +
        (finest - coarse->GetNumberOfPolys()) * k / 40;
      geomorph->SetTargetNumberOfTriangles(asked);
      geomorph->Update();
      worst = std::max(worst, asked - geomorph->GetOutput()->GetNumberOfPolys());
    }
    std::cerr << "  " << label << ": exact counts missed by at most " << worst << "\n";
    MESHLOD_CHECK_LE(worst, 2);
  }
  const PeerComparison c = CompareWithQuadricDecimation(input, coarse, label);
  MESHLOD_CHECK_LE(c.Ours.Hausdorff, (curvature ? 3.0 : 2.0) * c.Theirs.Hausdorff);
  MESHLOD_CHECK_LE(c.Ours.Rms, (curvature ? 3.0 : 1.5) * c.Theirs.Rms);
}

void TestNonOrientable()
{
  for (const bool curvature : { false, true })
  {
    CheckNonOrientable<vtkParametricMobius>("Moebius strip", curvature);
    CheckNonOrientable<vtkParametricBoy>("Boy's surface", curvature);
  }
}

// The Moebius strip with its normals: they differ across the seam, which then stays open with
// zero-area triangles along it and locks the collapses there. Pushed to 1% the last level is
// distorted (Hausdorff 26% of the diagonal; its estimated error 62 times the level before's),
// and a warning says so. Without the normals the seam is stitched: no such warning.
void TestErrorJumpWarning()
{
  for (const bool normals : { true, false })
  {
    vtkNew<vtkParametricMobius> surface;
    vtkNew<vtkParametricFunctionSource> source;
    source->SetParametricFunction(surface);
    source->SetUResolution(100);
    source->SetVResolution(100);
    source->GenerateTextureCoordinatesOff();
    source->SetGenerateNormals(normals);
    source->SetScalarModeToNone();
    vtkNew<vtkTest::ErrorObserver> warnings;
    vtkNew<vtkTriangleCollapseDecimation> filter;
    filter->AddObserver(vtkCommand::WarningEvent, warnings);
    filter->SetInputData(testing::TriangulateAndClean(source));
    filter->SetTargetReduction(0.99);
    filter->Update();
    const std::string text = warnings->GetWarningMessage();
    const bool jump = text.find("estimated error") != std::string::npos;
    std::cerr << "  Moebius strip " << (normals ? "with" : "without") << " normals: "
              << (jump ? "error-jump warning" : "no error-jump warning") << "\n";
    MESHLOD_CHECK_EQ(jump, normals);
  }
  // With PreserveTopology off a small closed piece vanishes, and its level's estimated error
  // jumps to about the piece's size: the warning names that cause (it named broken inputs
  // alone), and only then.
  // (A sphere of 16 x 16 and four small ones of the same resolution beside it.)
  vtkNew<vtkAppendPolyData> both;
  const double balls[5][4] = { { 0, 0, 0, 1.0 }, { 3, 0, 0, 0.05 }, { 0, 3, 0, 0.05 },
    { 0, 0, 3, 0.1 }, { 3, 3, 3, 0.02 } };
  for (const auto& ball : balls)
  {
    vtkNew<vtkSphereSource> sphere;
    sphere->SetCenter(ball[0], ball[1], ball[2]);
    sphere->SetRadius(ball[3]);
    sphere->SetThetaResolution(16);
    sphere->SetPhiResolution(16);
    both->AddInputConnection(sphere->GetOutputPort());
  }
  vtkSmartPointer<vtkPolyData> pieces = testing::TriangulateAndClean(both);
  for (const bool preserve : { true, false })
  {
    vtkNew<vtkTest::ErrorObserver> warnings;
    vtkNew<vtkTriangleCollapseDecimation> filter;
    filter->AddObserver(vtkCommand::WarningEvent, warnings);
    filter->SetInputData(pieces);
    filter->SetPreserveTopology(preserve);
    filter->SetTargetReduction(0.99);
    filter->Update();
    const std::string text = warnings->GetWarningMessage();
    std::cerr << "  sphere and small spheres, PreserveTopology " << preserve << ": "
              << (text.empty() ? "no warning" : text) << "\n";
    MESHLOD_CHECK_EQ(text.find("closed piece that vanishes") != std::string::npos, !preserve);
  }
}

// A CAD-like solid with sharp rims along curves: a flower-shaped polygon (r = 1 + 0.3 sin 5a,
// 200 corners) extruded and subdivided to 48,148 triangles. With paper 000's rule against new
// valence-3 vertices applied to edge collapses too, the 1% level had 1.9x vtkQuadricDecimation's
// Hausdorff distance and 2.0x its RMS distance (on 79,544 triangles, 5x and 4.8x); the rule now
// holds for triangle collapses only, as the paper states it.
void TestExtrudedSolid()
{
  const int corners = 200;
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> outline;
  outline->InsertNextCell(corners);
  for (int i = 0; i < corners; ++i)
  {
    const double a = 2.0 * vtkMath::Pi() * i / corners;
    const double r = 1.0 + 0.3 * std::sin(5.0 * a);
    outline->InsertCellPoint(points->InsertNextPoint(r * std::cos(a), r * std::sin(a), 0.0));
  }
  vtkNew<vtkPolyData> flower;
  flower->SetPoints(points);
  flower->SetPolys(outline);
  vtkNew<vtkTriangleFilter> cap;
  cap->SetInputData(flower);
  vtkNew<vtkLinearExtrusionFilter> extrude;
  extrude->SetInputConnection(cap->GetOutputPort());
  extrude->SetExtrusionTypeToVectorExtrusion();
  extrude->SetVector(0.0, 0.0, 0.3);
  extrude->CappingOn();
  vtkNew<vtkAdaptiveSubdivisionFilter> subdivide;
  subdivide->SetInputData(testing::TriangulateAndClean(extrude));
  subdivide->SetMaximumEdgeLength(0.05);
  subdivide->SetMaximumNumberOfPasses(100);
  subdivide->SetMaximumNumberOfTriangles(VTK_ID_MAX);
  vtkNew<vtkCleanPolyData> solid;
  solid->SetInputConnection(subdivide->GetOutputPort());
  solid->Update();
  vtkPolyData* input = solid->GetOutput();
  const vtkIdType n = input->GetNumberOfPolys();

  vtkNew<vtkTriangleCollapseDecimation> filter;
  filter->SetInputData(input);
  filter->AddLevelReduction(0.9);
  filter->AddLevelReduction(0.99);
  filter->Update();
  vtkMultiBlockDataSet* h = filter->GetHierarchy();
  MESHLOD_REQUIRE_EQ(h->GetNumberOfBlocks(), 3u);
  vtkPolyData* coarse = Level(h, 2);
  MESHLOD_CHECK_LE(coarse->GetNumberOfPolys(), n / 100 + 1);
  const PeerComparison c = CompareWithQuadricDecimation(
    input, coarse, "extruded solid (" + std::to_string(n) + " triangles)");
  MESHLOD_CHECK_LE(c.Ours.Rms, 1.5 * c.Theirs.Rms);
  MESHLOD_CHECK_LE(c.Ours.Hausdorff, 1.6 * c.Theirs.Hausdorff);
  const testing::MeshReport report = testing::InspectMesh(coarse);
  MESHLOD_CHECK_EQ(report.NonManifoldEdges, 0);
  MESHLOD_CHECK_EQ(report.BoundaryEdges, 0);
}

// Far from the origin (world or map coordinates) a quadric's evaluation cancels away the error
// it measures unless the engine works about the mesh's centre: the same sphere decimated at
// (1e6, -2e6, 3e5) must be as accurate as at the origin (measured without the centring: 1.9
// times the Hausdorff distance at 10%), and its levels must stay where the input is.
void TestFarFromOrigin()
{
  vtkSmartPointer<vtkPolyData> sphere = testing::MakeIcosphere(5);
  vtkNew<vtkPolyData> far;
  {
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    for (vtkIdType p = 0; p < sphere->GetNumberOfPoints(); ++p)
    {
      double x[3];
      sphere->GetPoint(p, x);
      points->InsertNextPoint(x[0] + 1e6, x[1] - 2e6, x[2] + 3e5);
    }
    far->SetPoints(points);
    far->SetPolys(sphere->GetPolys());
  }
  SurfaceDistanceOptions options;
  options.SamplesPerSurface = 20000;
  double hausdorff[2] = { 0.0, 0.0 };
  vtkPolyData* inputs[2] = { sphere, far };
  for (int i = 0; i < 2; ++i)
  {
    vtkNew<vtkTriangleCollapseDecimation> filter;
    filter->SetInputData(inputs[i]);
    filter->SetNumberOfLevels(1);
    filter->SetTargetReduction(0.9);
    filter->Update();
    vtkPolyData* coarse = Level(filter->GetHierarchy(), 1);
    MESHLOD_REQUIRE(coarse != nullptr);
    hausdorff[i] = MeasureSurfaceDistance(inputs[i], coarse, options).Hausdorff;
    double bounds[6];
    coarse->GetBounds(bounds);
    MESHLOD_CHECK_NEAR(0.5 * (bounds[0] + bounds[1]), i == 0 ? 0.0 : 1e6, 0.05);
  }
  std::cerr << "  sphere at 10%: Hausdorff " << hausdorff[0] << " at the origin, " << hausdorff[1]
            << " far from it\n";
  MESHLOD_CHECK_LE(hausdorff[1], 1.3 * hausdorff[0]);
}

// The curvature method's fits read the input's own points, through the map from the engine's
// vertices to the input's points and less the engine's centre, instead of a copy: far from the
// origin, an input with an unused point in front (every engine vertex then reads the input point
// after its own id) must give exactly the levels of the same input without it, with float points
// and with double points, and double points stored one array per component (which the engine
// copies instead) the same levels again.
std::vector<double> CoarsestCurvatureLevel(vtkPolyData* input)
{
  vtkNew<vtkTriangleCollapseDecimation> filter;
  filter->SetInputData(input);
  filter->SetMethodToCurvature();
  filter->SetNumberOfLevels(2);
  filter->SetTargetReduction(0.9);
  filter->Update();
  std::vector<double> points;
  vtkPolyData* coarse = Level(filter->GetHierarchy(), 2);
  for (vtkIdType p = 0; coarse && p < coarse->GetNumberOfPoints(); ++p)
  {
    double x[3];
    coarse->GetPoint(p, x);
    points.insert(points.end(), x, x + 3);
  }
  return points;
}

void TestCurvatureReadsInputPoints()
{
  vtkSmartPointer<vtkPolyData> surface = testing::MakeBumpySphereWithHoles(4);
  const double offset[3] = { 1.0e5, -3.0e4, 512.0 };
  vtkNew<vtkCellArray> shiftedPolys;
  for (const testing::TriangleIds& t : testing::Triangles(surface))
  {
    const vtkIdType ids[3] = { t[0] + 1, t[1] + 1, t[2] + 1 };
    shiftedPolys->InsertNextCell(3, ids);
  }
  const auto point = [&](vtkIdType p, double x[3]) {
    surface->GetPoint(p, x);
    for (int k = 0; k < 3; ++k)
    {
      x[k] += offset[k];
    }
  };
  for (const int type : { VTK_FLOAT, VTK_DOUBLE })
  {
    vtkNew<vtkPoints> points, padded;
    points->SetDataType(type);
    padded->SetDataType(type);
    padded->InsertNextPoint(5.0, 5.0, 5.0); // used by no triangle
    for (vtkIdType p = 0; p < surface->GetNumberOfPoints(); ++p)
    {
      double x[3];
      point(p, x);
      points->InsertNextPoint(x);
      padded->InsertNextPoint(x);
    }
    vtkNew<vtkPolyData> plain, shifted;
    plain->SetPoints(points);
    plain->SetPolys(surface->GetPolys());
    shifted->SetPoints(padded);
    shifted->SetPolys(shiftedPolys);
    const std::vector<double> expected = CoarsestCurvatureLevel(plain);
    MESHLOD_CHECK_GT(expected.size(), 300u);
    MESHLOD_CHECK(CoarsestCurvatureLevel(shifted) == expected);
    if (type == VTK_DOUBLE)
    {
      vtkNew<vtkSOADataArrayTemplate<double>> components;
      components->SetNumberOfComponents(3);
      components->SetNumberOfTuples(surface->GetNumberOfPoints());
      for (vtkIdType p = 0; p < surface->GetNumberOfPoints(); ++p)
      {
        double x[3];
        point(p, x);
        components->SetTuple(p, x);
      }
      vtkNew<vtkPoints> copied;
      copied->SetData(components);
      vtkNew<vtkPolyData> separate;
      separate->SetPoints(copied);
      separate->SetPolys(surface->GetPolys());
      MESHLOD_CHECK(CoarsestCurvatureLevel(separate) == expected);
    }
  }
}
} // namespace

int TestTriangleCollapseShapes(int, char*[])
{
  TestFlatGrid();
  TestFacetedCylinder();
  TestFlatFacedBox();
  TestRectangularBoxes();
  TestParametricSeam();
  TestHighValenceFan();
  TestFlatFanInRing();
  TestHighValenceFanIndependentSets();
  TestIndependentSetsStall();
  TestFarFromOrigin();
  TestNoisySurface();
  TestSurfaceWithHoles();
  TestLargestBoundaryWeight();
  TestNoisySurfaceCurvature(vtkTriangleCollapseDecimation::WEIGHT, 4.0, 4.0);
  TestCurvatureReadsInputPoints();
  TestNoisySurfaceCurvature(vtkTriangleCollapseDecimation::FIT_DEVIATION, 5.0, 6.0);
  TestSmoothSphereCurvature();
  TestNonOrientable();
  TestErrorJumpWarning();
  TestExtrudedSolid();
  return meshlod::testing::Result();
}
