// How vtkTriangleCollapseDecimation's quadric method weighs: PlaneWeights (the quadrics' planes
// weighted by their triangle's area, the default, or all alike, the input's mean triangle area)
// and AreaNormalization (a collapse's quadric value divided by the surface it stands for, to
// that power).
//
// - exact quadrics and surface weights on a hand-made fan of two triangles of different areas;
// - on a UV sphere, whose triangles shrink towards the poles, uniform weights keep more of the
//   coarse level's vertices near the poles (the input spends its triangles there), and so does
//   a higher AreaNormalization (small polar collapses lose their discount);
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

#include <cmath>
#include <iostream>
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
  MESHLOD_CHECK_EQ(byArea->GetNumberOfBlocks(), 3u);
  MESHLOD_CHECK_EQ(uniform->GetNumberOfBlocks(), 3u);
  if (byArea->GetNumberOfBlocks() != 3 || uniform->GetNumberOfBlocks() != 3)
  {
    return;
  }
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
  MESHLOD_CHECK(coarse != nullptr && coarseScaled != nullptr);
  if (!coarse || !coarseScaled)
  {
    return;
  }
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

Evaluated EvaluateOnIcosphere(double areaNormalization, CollapseMethod method)
{
  vtkNew<vtkTriangleFilter> caller;
  InputMesh input;
  ReadInputMesh(testing::MakeIcosphere(2), caller, input);
  TriangleCollapseOptions options;
  options.Method = method;
  options.AreaNormalization = areaNormalization;
  OriginalPointReader original;
  original.Copy = input.Mesh.Points;
  CollapseMesh state;
  LevelTracker tracker;
  tracker.Initialize(input.Mesh.GetNumberOfPoints(), method == CollapseMethod::Curvature);
  state.Initialize(std::move(input.Mesh), std::move(input.Topology), 0.3, 1.0);
  const CollapseCostModel model(options, state, tracker, original);
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
  TestSettings();
  return testing::Result();
}
