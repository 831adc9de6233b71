// vtkTriangleCollapseDecimation's PlaneWeights: the quadrics' planes weighted by their
// triangle's area (the default) or all alike (the input's mean triangle area).
//
// - exact quadrics on a hand-made fan of two triangles of different areas;
// - on a UV sphere, whose triangles shrink towards the poles, uniform weights keep more of the
//   coarse level's vertices near the poles (the input spends its triangles there);
// - the levels are valid, the same for one thread and several, and scale exactly with an open
//   input.
#include "vtkTriangleCollapseDecimation.h"

#include "Core/CollapseMesh.h"
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
}

vtkSmartPointer<vtkPolyData> MakeUVSphere()
{
  vtkNew<vtkSphereSource> sphere; // radius 0.5
  sphere->SetThetaResolution(120);
  sphere->SetPhiResolution(60);
  return testing::TriangulateAndClean(sphere);
}

vtkSmartPointer<vtkMultiBlockDataSet> Reduce(vtkPolyData* input, int weights)
{
  vtkNew<vtkTriangleCollapseDecimation> filter;
  filter->SetInputData(input);
  filter->SetPlaneWeights(weights);
  filter->SetNumberOfLevels(2);
  filter->SetTargetReduction(0.9);
  filter->Update();
  return filter->GetHierarchy();
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

// At 10% of a UV sphere's 13,920 triangles the area-weighted level keeps 72 of its 697 points
// in the polar caps, the uniformly weighted one 95: the input's fine poles count for more.
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

  // Valid levels with the correspondence intact.
  MESHLOD_CHECK_EQ(testing::CountCorrespondenceViolations(uniform), 0);
  for (unsigned int i = 1; i < uniform->GetNumberOfBlocks(); ++i)
  {
    const testing::MeshReport report = testing::InspectMesh(testing::Level(uniform, i));
    MESHLOD_CHECK_EQ(report.NonManifoldEdges, 0);
    MESHLOD_CHECK_EQ(report.BoundaryEdges, 0);
    MESHLOD_CHECK_EQ(report.DegenerateTriangles, 0);
    MESHLOD_CHECK_EQ(report.EulerCharacteristic, 2);
    MESHLOD_CHECK(report.ConsistentlyOriented);
  }

  // The mean area is summed in blocks of a fixed size: one thread and several agree (the
  // sphere is cut into more than one block only from 8,192 triangles: it has 13,920).
  const auto runs = testing::RunWithBothBackends([&] {
    vtkSmartPointer<vtkMultiBlockDataSet> h =
      Reduce(sphere, vtkTriangleCollapseDecimation::UNIFORM_WEIGHTS);
    return vtkSmartPointer<vtkPolyData>(testing::Level(h, 2));
  });
  MESHLOD_CHECK(testing::SameMesh(runs.first, runs.second));

  // Scaled by a power of two, an open hemisphere gives the same levels scaled: the surface
  // planes' weight, the mean area, scales as the boundary planes' (edge length times
  // diagonal), exactly. (A fixed weight would not: on a closed surface without boundary planes
  // any fixed weight scales alike, hence the open one.)
  vtkNew<vtkSphereSource> half;
  half->SetThetaResolution(120);
  half->SetPhiResolution(60);
  half->SetEndPhi(90.0);
  vtkSmartPointer<vtkPolyData> hemisphere = testing::TriangulateAndClean(half);
  vtkNew<vtkPolyData> scaled;
  scaled->DeepCopy(hemisphere);
  testing::Scale(scaled, 1024.0);
  vtkSmartPointer<vtkMultiBlockDataSet> unscaledLevels =
    Reduce(hemisphere, vtkTriangleCollapseDecimation::UNIFORM_WEIGHTS);
  vtkSmartPointer<vtkMultiBlockDataSet> scaledLevels =
    Reduce(scaled, vtkTriangleCollapseDecimation::UNIFORM_WEIGHTS);
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

void TestSettings()
{
  vtkNew<vtkTriangleCollapseDecimation> filter;
  MESHLOD_CHECK_EQ(filter->GetPlaneWeights(), vtkTriangleCollapseDecimation::AREA_WEIGHTS);
  MESHLOD_CHECK_EQ(std::string(filter->GetPlaneWeightsAsString()), "Area");
  filter->SetPlaneWeightsToUniform();
  MESHLOD_CHECK_EQ(std::string(filter->GetPlaneWeightsAsString()), "Uniform");
  filter->SetPlaneWeights(7); // clamped
  MESHLOD_CHECK_EQ(filter->GetPlaneWeights(), vtkTriangleCollapseDecimation::UNIFORM_WEIGHTS);
  std::ostringstream printed;
  filter->Print(printed);
  MESHLOD_CHECK(printed.str().find("PlaneWeights: Uniform") != std::string::npos);
}
} // namespace

int TestTriangleCollapsePlaneWeights(int, char*[])
{
  TestQuadricWeights();
  TestUVSphere();
  TestSettings();
  return testing::Result();
}
