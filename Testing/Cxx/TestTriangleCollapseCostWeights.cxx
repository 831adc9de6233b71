// How vtkTriangleCollapseDecimation's quadric method weighs: PlaneWeights (the quadrics' planes
// weighted by their triangle's area, the default, or all alike, the input's mean triangle area)
// and AreaNormalization (a collapse's quadric value divided by the surface it stands for, to
// that power).
//
// - exact quadrics and surface weights on a hand-made fan of two triangles of different areas;
// - on a UV sphere, whose triangles shrink towards the poles, uniform weights keep more of the
//   coarse level's vertices near the poles (the input spends its triangles there);
// - exact AreaNormalization costs on an icosphere, surface weights summed by a collapse, and
//   the triangle-or-edge choice the same as evaluating everything;
// - the levels are valid, the same for one thread and several, and scale exactly with an open
//   input; the curvature method ignores AreaNormalization.
#include "vtkTriangleCollapseDecimation.h"

#include "Core/CollapseCosts.h"
#include "Core/CollapseMesh.h"
#include "Core/LevelTracker.h"
#include "Core/TriangleCollapse.h"
#include "Core/TriangleMesh.h"
#include "MeshLODHierarchyChecks.h"
#include "MeshLODInputMesh.h"
#include "MeshLODTestCheck.h"
#include "MeshLODTestMeshes.h"

#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSphereSource.h"
#include "vtkTestErrorObserver.h"
#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkTriangleFilter.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>

namespace
{
using namespace meshlod;

// Two triangles on z = 0 sharing the edge from point 0 to point 1: areas 1 and 3 (a fan around
// point 0, open).
vtkSmartPointer<vtkPolyData> MakeUnequalPair()
{
  return testing::MakePolyData({ 0, 0, 0, 2, 0, 0, 0, 1, 0, 0, -3, 0 }, { 0, 1, 2, 0, 3, 1 });
}

// The quadric of point 0 weighs (its trace) the sum of its triangles' areas, 4, or each plane
// the mean area, 2 each: also 4 here; point 2 has only the triangle of area 1, which uniform
// weights raise to the mean, 2. (No boundary planes: boundaryWeight 0.)
void TestQuadricWeights()
{
  vtkSmartPointer<vtkPolyData> pair = MakeUnequalPair();
  vtkNew<vtkTriangleFilter> caller;
  InputMesh input;
  ReadInputMesh(pair, caller, input);
  MESHLOD_CHECK_EQ(input.Mesh.GetNumberOfTriangles(), 2);
  MESHLOD_CHECK_EQ(input.Mesh.MeanTriangleArea(), 2.0);

  CollapseMesh byArea;
  byArea.Initialize(TriangleMesh(input.Mesh), TriangleTopology(input.Topology), 0.0, 1.0);
  CollapseMesh uniform;
  uniform.Initialize(TriangleMesh(input.Mesh), TriangleTopology(input.Topology), 0.0, 1.0,
    input.Mesh.MeanTriangleArea());
  // (ReadInputMesh keeps the points in their order: every point is used.)
  std::cout << "point 2: area " << byArea.Quadrics[2].Weight() << ", uniform "
            << uniform.Quadrics[2].Weight() << "\n";
  MESHLOD_CHECK(std::abs(byArea.Quadrics[0].Weight() - 4.0) < 1e-12);
  MESHLOD_CHECK(std::abs(uniform.Quadrics[0].Weight() - 4.0) < 1e-12);
  MESHLOD_CHECK(std::abs(byArea.Quadrics[2].Weight() - 1.0) < 1e-12);
  MESHLOD_CHECK(std::abs(uniform.Quadrics[2].Weight() - 2.0) < 1e-12);
  MESHLOD_CHECK(std::abs(byArea.Quadrics[3].Weight() - 3.0) < 1e-12);
  MESHLOD_CHECK(std::abs(uniform.Quadrics[3].Weight() - 2.0) < 1e-12);

  // The surface weights (AreaNormalization's) are the surface planes' weights alone: boundary
  // planes (boundaryWeight 1 here; every edge of the pair but the shared one is a boundary)
  // raise the quadrics' weights, not these. Their unit is the mean triangle's weight, 2 both
  // ways.
  CollapseMesh withBoundary;
  withBoundary.Initialize(TriangleMesh(input.Mesh), TriangleTopology(input.Topology), 1.0, 1.0);
  CollapseMesh uniformWithBoundary;
  uniformWithBoundary.Initialize(TriangleMesh(input.Mesh), TriangleTopology(input.Topology),
    1.0, 1.0, input.Mesh.MeanTriangleArea());
  const double areas[4] = { 4.0, 4.0, 1.0, 3.0 };
  const double alike[4] = { 4.0, 4.0, 2.0, 2.0 };
  for (int p = 0; p < 4; ++p)
  {
    MESHLOD_CHECK_GT(withBoundary.Quadrics[p].Weight(), byArea.Quadrics[p].Weight() + 0.5);
    MESHLOD_CHECK(std::abs(withBoundary.SurfaceWeights[p] - areas[p]) < 1e-12);
    MESHLOD_CHECK(std::abs(byArea.SurfaceWeights[p] - areas[p]) < 1e-12);
    MESHLOD_CHECK(std::abs(uniformWithBoundary.SurfaceWeights[p] - alike[p]) < 1e-12);
  }
  MESHLOD_CHECK_EQ(withBoundary.SurfaceWeightUnit, 2.0);
  MESHLOD_CHECK_EQ(uniformWithBoundary.SurfaceWeightUnit, 2.0);
}

vtkSmartPointer<vtkPolyData> MakeUVSphere()
{
  vtkNew<vtkSphereSource> sphere; // radius 0.5
  sphere->SetThetaResolution(120);
  sphere->SetPhiResolution(60);
  return testing::TriangulateAndClean(sphere);
}

vtkSmartPointer<vtkMultiBlockDataSet> Reduce(
  vtkPolyData* input, int weights, double areaNormalization = 0.25, bool curvature = false)
{
  vtkNew<vtkTriangleCollapseDecimation> filter;
  filter->SetInputData(input);
  filter->SetPlaneWeights(weights);
  filter->SetAreaNormalization(areaNormalization);
  if (curvature)
  {
    filter->SetMethodToCurvature();
  }
  filter->SetNumberOfLevels(2);
  filter->SetTargetReduction(0.9);
  filter->Update();
  return filter->GetHierarchy();
}

// Valid levels of a closed sphere, with the correspondence intact.
void CheckSphereLevels(vtkMultiBlockDataSet* h)
{
  MESHLOD_CHECK_EQ(testing::CountCorrespondenceViolations(h), 0);
  for (unsigned int i = 1; i < h->GetNumberOfBlocks(); ++i)
  {
    const testing::MeshReport report = testing::InspectMesh(testing::Level(h, i));
    MESHLOD_CHECK_EQ(report.NonManifoldEdges, 0);
    MESHLOD_CHECK_EQ(report.BoundaryEdges, 0);
    MESHLOD_CHECK_EQ(report.DegenerateTriangles, 0);
    MESHLOD_CHECK_EQ(report.EulerCharacteristic, 2);
    MESHLOD_CHECK(report.ConsistentlyOriented);
  }
}

// Points of a mesh within the polar caps |z| > 0.45 of the radius-0.5 sphere.
int PolarPoints(vtkPolyData* mesh)
{
  int count = 0;
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    double x[3];
    mesh->GetPoint(p, x);
    count += std::abs(x[2]) > 0.45 ? 1 : 0;
  }
  return count;
}

// At 10% of a UV sphere's 13,920 triangles the area-weighted level keeps 70 of its 697 points
// in the polar caps, the uniformly weighted one 88 (72 and 95 with AreaNormalization 0): the
// input's fine poles count for more.
void TestUVSphere()
{
  vtkSmartPointer<vtkPolyData> sphere = MakeUVSphere();
  vtkSmartPointer<vtkMultiBlockDataSet> byArea = Reduce(sphere, vtkTriangleCollapseDecimation::AREA_WEIGHTS);
  vtkSmartPointer<vtkMultiBlockDataSet> uniform =
    Reduce(sphere, vtkTriangleCollapseDecimation::UNIFORM_WEIGHTS);
  MESHLOD_REQUIRE_EQ(byArea->GetNumberOfBlocks(), 3u);
  MESHLOD_REQUIRE_EQ(uniform->GetNumberOfBlocks(), 3u);
  vtkPolyData* coarseByArea = testing::Level(byArea, 2);
  vtkPolyData* coarseUniform = testing::Level(uniform, 2);
  const vtkIdType target = static_cast<vtkIdType>(std::floor(0.1 * sphere->GetNumberOfPolys()));
  MESHLOD_CHECK_LE(std::abs(coarseByArea->GetNumberOfPolys() - target), 3);
  MESHLOD_CHECK_LE(std::abs(coarseUniform->GetNumberOfPolys() - target), 3);
  const int polarByArea = PolarPoints(coarseByArea);
  const int polarUniform = PolarPoints(coarseUniform);
  std::cout << "UV sphere at 10%: polar points " << polarByArea << " (area weights), "
            << polarUniform << " (uniform weights) of " << coarseUniform->GetNumberOfPoints()
            << "\n";
  MESHLOD_CHECK_GE(polarUniform, 1.2 * polarByArea);

  CheckSphereLevels(uniform);

  // The mean area is summed in blocks of a fixed size: one thread and several agree (the
  // sphere is cut into more than one block only from 8,192 triangles: it has 13,920).
  const auto runs = testing::RunWithBothBackends([&] {
    vtkSmartPointer<vtkMultiBlockDataSet> h =
      Reduce(sphere, vtkTriangleCollapseDecimation::UNIFORM_WEIGHTS);
    return vtkSmartPointer<vtkPolyData>(testing::Level(h, 2));
  });
  MESHLOD_CHECK(testing::SameMesh(runs.first, runs.second));
}

// Scaled by a power of two, an open hemisphere gives the same levels scaled: with uniform
// weights the surface planes' weight, the mean area, scales as the boundary planes' (edge length
// times diagonal), exactly. (A fixed weight would not: on a closed surface without boundary
// planes any fixed weight scales alike, hence the open one.) The surface weights that
// AreaNormalization divides by are in units of the mean triangle's, so any power of them scales
// exactly too (0.7 takes pow, not a square root).
void TestExactScaling(int weights, double areaNormalization)
{
  vtkNew<vtkSphereSource> half;
  half->SetThetaResolution(120);
  half->SetPhiResolution(60);
  half->SetEndPhi(90.0);
  vtkSmartPointer<vtkPolyData> hemisphere = testing::TriangulateAndClean(half);
  vtkNew<vtkPolyData> scaled;
  scaled->DeepCopy(hemisphere);
  testing::Scale(scaled, 1024.0);
  vtkSmartPointer<vtkMultiBlockDataSet> unscaledLevels =
    Reduce(hemisphere, weights, areaNormalization);
  vtkSmartPointer<vtkMultiBlockDataSet> scaledLevels = Reduce(scaled, weights, areaNormalization);
  vtkPolyData* coarse = testing::Level(unscaledLevels, 2);
  vtkPolyData* coarseScaled = testing::Level(scaledLevels, 2);
  MESHLOD_REQUIRE(coarse != nullptr && coarseScaled != nullptr);
  MESHLOD_CHECK_GT(testing::InspectMesh(coarse).BoundaryEdges, 0);
  MESHLOD_CHECK_EQ(coarseScaled->GetNumberOfPolys(), coarse->GetNumberOfPolys());
  MESHLOD_CHECK_EQ(coarseScaled->GetNumberOfPoints(), coarse->GetNumberOfPoints());
  if (coarseScaled->GetNumberOfPoints() != coarse->GetNumberOfPoints())
  {
    return;
  }
  vtkIdType differing = 0;
  for (vtkIdType p = 0; p < coarse->GetNumberOfPoints(); ++p)
  {
    double a[3], b[3];
    coarse->GetPoint(p, a);
    coarseScaled->GetPoint(p, b);
    for (int k = 0; k < 3; ++k)
    {
      differing += 1024.0 * a[k] == b[k] ? 0 : 1;
    }
  }
  MESHLOD_CHECK_EQ(differing, 0);
}

// AreaNormalization, exactly: on an icosphere, a triangle's and an edge's cost is the merged
// quadric's value (their cost at 0) over the merged surface weight, in units of the mean
// triangle's, to the power; their error (the RMS distance to the planes) does not change; the
// curvature method ignores the setting.
struct Evaluated
{
  CollapseCandidate Triangle, Edge;
  double Surface = 0.0; // the triangle's three surface weights over the unit
  double EdgeSurface = 0.0;
};

// A collapse state of a mesh.
struct State
{
  TriangleCollapseOptions Options;
  OriginalPointReader Original;
  CollapseMesh Mesh;
  LevelTracker Tracker;
};

void Initialize(vtkPolyData* mesh, double areaNormalization, CollapseMethod method, State& state)
{
  vtkNew<vtkTriangleFilter> caller;
  InputMesh input;
  ReadInputMesh(mesh, caller, input);
  state.Options.Method = method;
  state.Options.AreaNormalization = areaNormalization;
  state.Original.Copy = input.Mesh.Points;
  state.Tracker.Initialize(input.Mesh.GetNumberOfPoints(), method == CollapseMethod::Curvature);
  state.Mesh.Initialize(std::move(input.Mesh), std::move(input.Topology), 0.3, 1.0);
}

Evaluated EvaluateOnIcosphere(double areaNormalization, CollapseMethod method)
{
  State all;
  Initialize(testing::MakeIcosphere(2), areaNormalization, method, all);
  CollapseMesh& state = all.Mesh;
  const CollapseCostModel model(all.Options, state, all.Tracker, all.Original);
  CostScratch scratch;
  Evaluated e;
  const Id t = 17;
  const Id* tri = state.Mesh.Triangle(t);
  MESHLOD_CHECK(model.EvaluateTriple(tri, e.Triangle, scratch));
  MESHLOD_CHECK(model.EvaluateChoice(t, 1, e.Edge, scratch));
  const std::vector<double>& w = state.SurfaceWeights;
  e.Surface = (w[tri[0]] + w[tri[1]] + w[tri[2]]) / state.SurfaceWeightUnit;
  e.EdgeSurface = (w[tri[1]] + w[tri[2]]) / state.SurfaceWeightUnit;
  return e;
}

// The cost model's choice for each triangle (TRIANGLES_AND_EDGES: the triangle when it costs
// at most its cheapest edge times TriangleCostFactor, which its cost is divided by) is the one
// found by evaluating the three edges and the triangle: the shortcut that skips the triangle
// when its edges alone rule it out changes nothing. On a slightly rough sphere: at powers 0 and
// 0.25 no triangle is chosen on the first evaluation (merging three vertices costs more than
// 1.5 edges), at 1 most are (919 of 1,280: a triangle's surface is half again an edge's).
void TestTriangleOrEdge(double areaNormalization)
{
  vtkSmartPointer<vtkPolyData> rough = testing::MakeIcosphere(3);
  testing::PerturbRadially(rough, 0.002, 5);
  State all;
  Initialize(rough, areaNormalization, CollapseMethod::Quadric, all);
  const CollapseCostModel model(all.Options, all.Mesh, all.Tracker, all.Original);
  CostScratch scratch;
  int triangles = 0, mismatches = 0;
  for (Id t = 0; t < all.Mesh.Mesh.GetNumberOfTriangles(); ++t)
  {
    CollapseCandidate chosen, triangle, edge, best;
    MESHLOD_CHECK(model.Evaluate(t, chosen, scratch));
    MESHLOD_CHECK(model.EvaluateTriple(all.Mesh.Mesh.Triangle(t), triangle, scratch));
    best.Cost = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k)
    {
      MESHLOD_CHECK(model.EvaluateChoice(t, k, edge, scratch));
      best = edge.Cost < best.Cost ? edge : best;
    }
    const CollapseCandidate& expected = triangle.Cost <= best.Cost ? triangle : best;
    triangles += expected.Choice == TriangleChoice ? 1 : 0;
    mismatches += chosen.Choice != expected.Choice || chosen.Cost != expected.Cost ? 1 : 0;
  }
  std::cout << "AreaNormalization " << areaNormalization << ": " << triangles << " of "
            << all.Mesh.Mesh.GetNumberOfTriangles() << " triangles collapse whole, "
            << mismatches << " choices differ from evaluating everything\n";
  MESHLOD_CHECK_EQ(mismatches, 0);
  if (areaNormalization == 1.0)
  {
    MESHLOD_CHECK_GT(triangles, 500);
  }
}

// Around a hub (more than FanTriangleLimit triangles at a vertex) a triangle is priced by its
// edge away from the hub only: in a flat fan of 100 triangles inside a ring, where every
// collapse costs 0 and the triangle collapse wins the tie, each fan triangle's choice is its
// rim edge. In a fan of 40 each chooses the triangle, which moves the centre.
void TestHubTriangles()
{
  for (const int n : { 100, 40 })
  {
    State all;
    Initialize(testing::MakeFlatFanInRing(n), 0.25, CollapseMethod::Quadric, all);
    const CollapseCostModel model(all.Options, all.Mesh, all.Tracker, all.Original);
    CostScratch scratch;
    int atCentre = 0, rimEdges = 0;
    for (Id t = 0; t < all.Mesh.Mesh.GetNumberOfTriangles(); ++t)
    {
      const Id* tri = all.Mesh.Mesh.Triangle(t);
      if (std::find(tri, tri + 3, 0) == tri + 3)
      {
        continue; // a triangle of the ring
      }
      CollapseCandidate chosen;
      MESHLOD_CHECK(model.Evaluate(t, chosen, scratch));
      const Id* members = chosen.Members;
      const bool centre = std::find(members, members + chosen.MemberCount, 0) !=
        members + chosen.MemberCount;
      atCentre += centre ? 1 : 0;
      rimEdges += !centre && chosen.MemberCount == 2 ? 1 : 0;
    }
    std::cout << "flat fan of " << n << ": " << atCentre << " choices move the centre, "
              << rimEdges << " are rim edges\n";
    MESHLOD_CHECK_EQ(n > FanTriangleLimit ? rimEdges : atCentre, n);
  }
}

// A collapse sums its vertices' surface weights into the survivor; the total stays.
void TestSurfaceWeightsMerge()
{
  State all;
  Initialize(testing::MakeIcosphere(2), 0.25, CollapseMethod::Quadric, all);
  CollapseMesh& state = all.Mesh;
  double total = 0.0;
  for (const double w : state.SurfaceWeights)
  {
    total += w;
  }
  Star star;
  const Id* tri = state.Mesh.Triangle(40);
  const Id members[2] = { tri[0], tri[1] };
  MESHLOD_CHECK(state.GatherStar(members, 2, star));
  const double expected = state.SurfaceWeights[members[0]] + state.SurfaceWeights[members[1]];
  double x[3];
  for (int c = 0; c < 3; ++c)
  {
    x[c] = 0.5 * (state.Mesh.Point(members[0])[c] + state.Mesh.Point(members[1])[c]);
  }
  const Id survivor = state.Apply(star, x);
  MESHLOD_CHECK(survivor == members[0] || survivor == members[1]);
  MESHLOD_CHECK_EQ(state.SurfaceWeights[survivor], expected);
  double after = 0.0;
  for (Id v = 0; v < state.Mesh.GetNumberOfPoints(); ++v)
  {
    after += state.Survivor[v] == v ? state.SurfaceWeights[v] : 0.0;
  }
  MESHLOD_CHECK_LE(std::abs(after - total), 1e-12 * total);
}

void TestAreaNormalization()
{
  const Evaluated plain = EvaluateOnIcosphere(0.0, CollapseMethod::Quadric);
  MESHLOD_CHECK_GT(plain.Triangle.Cost, 0.0);
  MESHLOD_CHECK_GT(plain.Edge.Cost, 0.0);
  MESHLOD_CHECK_EQ(plain.Edge.MemberCount, 2);
  // An icosphere's triangles are nearly equal, and each plane goes to its three corners whole:
  // a corner stands for its 5 or 6 triangles, a triangle for 15 to 18 mean triangles.
  MESHLOD_CHECK_GT(plain.Surface, 14.0);
  MESHLOD_CHECK_LT(plain.Surface, 19.0);
  for (const double power : { 0.25, 0.5, 0.7, 1.0 })
  {
    const Evaluated scaled = EvaluateOnIcosphere(power, CollapseMethod::Quadric);
    const double triangle = plain.Triangle.Cost / std::pow(plain.Surface, power);
    const double edge = plain.Edge.Cost / std::pow(plain.EdgeSurface, power);
    std::cout << "AreaNormalization " << power << ": triangle cost " << scaled.Triangle.Cost
              << " (expected " << triangle << "), edge cost " << scaled.Edge.Cost
              << " (expected " << edge << ")\n";
    MESHLOD_CHECK_LE(std::abs(scaled.Triangle.Cost - triangle), 1e-12 * triangle);
    MESHLOD_CHECK_LE(std::abs(scaled.Edge.Cost - edge), 1e-12 * edge);
    MESHLOD_CHECK_EQ(scaled.Triangle.Error, plain.Triangle.Error);
    MESHLOD_CHECK_EQ(scaled.Edge.Error, plain.Edge.Error);
    for (int k = 0; k < 3; ++k)
    {
      MESHLOD_CHECK_EQ(scaled.Triangle.Position[k], plain.Triangle.Position[k]);
    }
  }
  const Evaluated curvature = EvaluateOnIcosphere(0.0, CollapseMethod::Curvature);
  const Evaluated curvatureNormalized = EvaluateOnIcosphere(1.0, CollapseMethod::Curvature);
  MESHLOD_CHECK_EQ(curvatureNormalized.Triangle.Cost, curvature.Triangle.Cost);
  MESHLOD_CHECK_EQ(curvatureNormalized.Edge.Cost, curvature.Edge.Cost);

  // Through the filter: other levels than paper 002's cost, valid ones.
  vtkSmartPointer<vtkPolyData> sphere = MakeUVSphere();
  vtkSmartPointer<vtkMultiBlockDataSet> paper =
    Reduce(sphere, vtkTriangleCollapseDecimation::AREA_WEIGHTS, 0.0);
  vtkSmartPointer<vtkMultiBlockDataSet> normalized =
    Reduce(sphere, vtkTriangleCollapseDecimation::AREA_WEIGHTS, 1.0);
  MESHLOD_CHECK_EQ(testing::CountDifferingLevels(paper, normalized), 2);
  CheckSphereLevels(normalized);
}

void TestSettings()
{
  vtkNew<vtkTriangleCollapseDecimation> filter;
  MESHLOD_CHECK_EQ(filter->GetAreaNormalization(), 0.25);
  filter->SetAreaNormalization(2.0); // clamped
  MESHLOD_CHECK_EQ(filter->GetAreaNormalization(), 1.0);
  filter->SetAreaNormalization(-1.0);
  MESHLOD_CHECK_EQ(filter->GetAreaNormalization(), 0.0);
  MESHLOD_CHECK_EQ(filter->GetPlaneWeights(), vtkTriangleCollapseDecimation::AREA_WEIGHTS);
  MESHLOD_CHECK_EQ(std::string(filter->GetPlaneWeightsAsString()), "Area");
  filter->SetPlaneWeightsToUniform();
  MESHLOD_CHECK_EQ(std::string(filter->GetPlaneWeightsAsString()), "Uniform");
  filter->SetPlaneWeights(7); // clamped
  MESHLOD_CHECK_EQ(filter->GetPlaneWeights(), vtkTriangleCollapseDecimation::UNIFORM_WEIGHTS);
  std::ostringstream printed;
  filter->Print(printed);
  MESHLOD_CHECK(printed.str().find("PlaneWeights: Uniform") != std::string::npos);
  MESHLOD_CHECK(printed.str().find("AreaNormalization: 0\n") != std::string::npos);

  // NaN passes the clamp; it is an error naming the setting, with no level made.
  vtkNew<vtkTest::ErrorObserver> observer;
  filter->AddObserver(vtkCommand::ErrorEvent, observer);
  filter->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, observer);
  filter->SetInputData(MakeUVSphere());
  filter->SetAreaNormalization(std::nan(""));
  filter->Update();
  MESHLOD_CHECK(observer->GetErrorMessage().find("AreaNormalization is NaN") != std::string::npos);
  MESHLOD_CHECK_EQ(filter->GetHierarchy()->GetNumberOfBlocks(), 0u);
}
} // namespace

int TestTriangleCollapseCostWeights(int, char*[])
{
  TestQuadricWeights();
  TestUVSphere();
  TestExactScaling(vtkTriangleCollapseDecimation::UNIFORM_WEIGHTS, 0.25);
  TestExactScaling(vtkTriangleCollapseDecimation::AREA_WEIGHTS, 0.7);
  TestAreaNormalization();
  for (const double power : { 0.0, 0.25, 1.0 })
  {
    TestTriangleOrEdge(power);
  }
  TestSurfaceWeightsMerge();
  TestHubTriangles();
  TestSettings();
  return testing::Result();
}
