// CenterOnInput (Core/LevelCentering) in both filters: on a closed curved isosurface the levels
// sit centred on the input (mean signed distance near zero instead of to the outside) and are
// closer to it; the hierarchy's correspondence holds; boundary points and flat parts do not
// move, nor do the points of a faceted solid with sharp edges; the triangles are those of the
// uncentred run.
#include "Core/LevelCentering.h"
#include "MeshLODHierarchyChecks.h"
#include "MeshLODSurfaceDistance.h"
#include "MeshLODTestCheck.h"
#include "MeshLODTestMeshes.h"
#include "vtkTriangleCollapseDecimation.h"
#include "vtkVertexClusterOctree.h"

#include "vtkCellArray.h"
#include "vtkImplicitPolyDataDistance.h"
#include "vtkLinearExtrusionFilter.h"
#include "vtkLinearSubdivisionFilter.h"
#include "vtkMath.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkTriangle.h"

#include <cmath>
#include <iostream>
#include <set>
#include <string>
#include <utility>

namespace
{
using namespace meshlod;
using testing::Level;

vtkSmartPointer<vtkMultiBlockDataSet> Decimate(vtkPolyData* mesh, bool center)
{
  vtkNew<vtkTriangleCollapseDecimation> filter;
  filter->SetInputData(mesh);
  filter->SetNumberOfLevels(3);
  filter->SetTargetReduction(0.98);
  filter->SetCenterOnInput(center);
  filter->Update();
  return filter->GetHierarchy();
}

vtkSmartPointer<vtkMultiBlockDataSet> Cluster(vtkPolyData* mesh, bool center)
{
  vtkNew<vtkVertexClusterOctree> filter;
  filter->SetInputData(mesh);
  filter->SetLevelModeToTargetTriangleCounts();
  filter->AddTargetTriangleCount(mesh->GetNumberOfPolys() / 10);
  filter->AddTargetTriangleCount(mesh->GetNumberOfPolys() / 50);
  filter->SetCenterOnInput(center);
  filter->Update();
  return filter->GetHierarchy();
}

// Mean signed distance of the input's surface to `level` (its triangles' centroids, weighted
// by area; negative: the level lies outside the input).
double MeanSignedDistance(vtkPolyData* input, vtkPolyData* level)
{
  vtkNew<vtkImplicitPolyDataDistance> distance;
  distance->SetInput(level);
  double sum = 0.0, total = 0.0;
  for (const auto& tri : testing::Triangles(input))
  {
    double p[3][3], centroid[3];
    for (int c = 0; c < 3; ++c)
    {
      input->GetPoint(tri[c], p[c]);
    }
    for (int k = 0; k < 3; ++k)
    {
      centroid[k] = (p[0][k] + p[1][k] + p[2][k]) / 3.0;
    }
    const double area = vtkTriangle::TriangleArea(p[0], p[1], p[2]);
    sum += area * distance->EvaluateFunction(centroid);
    total += area;
  }
  return sum / total;
}

// Closed and curved: every level centred, closer to the input, same triangles as uncentred.
void TestCurvedSurface(const std::string& name,
  vtkPolyData* input,
  vtkSmartPointer<vtkMultiBlockDataSet> (*make)(vtkPolyData*, bool))
{
  const auto plain = make(input, false);
  const auto centred = make(input, true);
  MESHLOD_CHECK_EQ(centred->GetNumberOfBlocks(), plain->GetNumberOfBlocks());
  MESHLOD_CHECK_EQ(testing::CountCorrespondenceViolations(centred), 0);
  const unsigned int coarsest = centred->GetNumberOfBlocks() - 1;
  MESHLOD_CHECK_GE(coarsest, 2u);
  SurfaceDistanceOptions options;
  options.SamplesPerSurface = 40000;
  for (unsigned int i = 1; i <= coarsest && i < plain->GetNumberOfBlocks(); ++i)
  {
    vtkPolyData* a = Level(plain, i);
    vtkPolyData* b = Level(centred, i);
    MESHLOD_CHECK(testing::Triangles(a) == testing::Triangles(b));
    const testing::MeshReport report = testing::InspectMesh(b);
    MESHLOD_CHECK_EQ(report.NonManifoldEdges, 0);
    MESHLOD_CHECK_EQ(report.BoundaryEdges, 0);
    MESHLOD_CHECK_EQ(report.DegenerateTriangles, 0);
    MESHLOD_CHECK_EQ(testing::CountFlippedTriangles(input, b), 0);
    const SurfaceDistance before = MeasureSurfaceDistance(input, a, options);
    const SurfaceDistance after = MeasureSurfaceDistance(input, b, options);
    const double meanBefore = MeanSignedDistance(input, a);
    const double meanAfter = MeanSignedDistance(input, b);
    std::cerr << "  " << name << ", level " << i << " (" << b->GetNumberOfPolys()
              << " triangles): RMS " << before.Rms << " -> " << after.Rms << ", Hausdorff "
              << before.Hausdorff << " -> " << after.Hausdorff << ", mean signed distance "
              << meanBefore << " -> " << meanAfter << "\n";
    if (b->GetNumberOfPolys() > LevelCentering::LargestFraction * input->GetNumberOfPolys())
    {
      MESHLOD_CHECK(testing::SameMesh(a, b)); // too fine to be centred
      continue;
    }
    // The quadric places the points outside a convex blob: the input lies inside the level.
    MESHLOD_CHECK_LT(meanBefore, -0.3 * before.Rms);
    // Most of the offset removed (not all: no point moves so far that the largest deviation
    // around it grows).
    MESHLOD_CHECK_LT(std::abs(meanAfter), 0.6 * std::abs(meanBefore));
    if (i == coarsest)
    {
      MESHLOD_CHECK_LE(after.Rms, 0.9 * before.Rms);
      MESHLOD_CHECK_LE(after.Hausdorff, 1.1 * before.Hausdorff);
    }
  }
}

// Open and partly flat: boundary points and the points of the flat part stay exactly where the
// uncentred run puts them.
void TestBoundaryAndFlatParts()
{
  // A flat grid with a bump in its middle.
  vtkSmartPointer<vtkPolyData> grid = testing::MakeGrid(60, 60);
  double bounds[6];
  grid->GetBounds(bounds);
  const double cx = 0.5 * (bounds[0] + bounds[1]), cy = 0.5 * (bounds[2] + bounds[3]);
  const double size = bounds[1] - bounds[0];
  for (vtkIdType p = 0; p < grid->GetNumberOfPoints(); ++p)
  {
    double x[3];
    grid->GetPoint(p, x);
    const double r2 = ((x[0] - cx) * (x[0] - cx) + (x[1] - cy) * (x[1] - cy)) / (size * size);
    x[2] = r2 < 0.04 ? 0.1 * size * (0.04 - r2) / 0.04 * (0.04 - r2) / 0.04 : 0.0;
    grid->GetPoints()->SetPoint(p, x);
  }
  const auto plain = Decimate(grid, false);
  const auto centred = Decimate(grid, true);
  MESHLOD_CHECK_EQ(centred->GetNumberOfBlocks(), plain->GetNumberOfBlocks());
  MESHLOD_CHECK_EQ(testing::CountCorrespondenceViolations(centred), 0);
  vtkIdType moved = 0;
  for (unsigned int i = 1; i < centred->GetNumberOfBlocks() && i < plain->GetNumberOfBlocks(); ++i)
  {
    vtkPolyData* a = Level(plain, i);
    vtkPolyData* b = Level(centred, i);
    MESHLOD_CHECK(testing::Triangles(a) == testing::Triangles(b));
    // Boundary points: those on an edge of one triangle.
    std::set<std::pair<vtkIdType, vtkIdType>> once, twice;
    for (const auto& tri : testing::Triangles(b))
    {
      for (int k = 0; k < 3; ++k)
      {
        const auto edge = std::minmax(tri[k], tri[(k + 1) % 3]);
        if (!once.insert(edge).second)
        {
          twice.insert(edge);
        }
      }
    }
    std::set<vtkIdType> boundary;
    for (const auto& edge : once)
    {
      if (!twice.count(edge))
      {
        boundary.insert(edge.first);
        boundary.insert(edge.second);
      }
    }
    MESHLOD_CHECK(!boundary.empty());
    for (vtkIdType p = 0; p < b->GetNumberOfPoints(); ++p)
    {
      double x[3], y[3];
      a->GetPoint(p, x);
      b->GetPoint(p, y);
      const bool same = x[0] == y[0] && x[1] == y[1] && x[2] == y[2];
      if (boundary.count(p) || x[2] == 0.0)
      {
        MESHLOD_CHECK(same); // on the boundary or on the flat part
      }
      moved += same ? 0 : 1;
    }
  }
  // The bump's points do move.
  MESHLOD_CHECK_GT(moved, 0);
}
// A faceted solid: a six-pointed star's prism (walls meeting at 15 degrees and at sharp
// tips), subdivided. Its levels down to 50 triangles are exact, and centring must keep them
// so. A sample on one wall next to a sharp tip also projects into the other wall's triangles
// there, at a distance: when it counted for the first triangle it projected into instead of
// the one it lies on, the flat walls' points beside the tips moved off the surface (0.74% of
// the diagonal at 500 and 280 triangles).
void TestFacetedSolid()
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> outline;
  constexpr int Tips = 6;
  outline->InsertNextCell(2 * Tips);
  for (int i = 0; i < 2 * Tips; ++i)
  {
    const double angle = vtkMath::Pi() * i / Tips, radius = i % 2 == 0 ? 1.0 : 0.5;
    outline->InsertCellPoint(
      points->InsertNextPoint(radius * std::cos(angle), radius * std::sin(angle), 0.0));
  }
  vtkNew<vtkPolyData> star;
  star->SetPoints(points);
  star->SetPolys(outline);
  vtkNew<vtkLinearExtrusionFilter> extrude;
  extrude->SetInputData(star);
  extrude->SetExtrusionTypeToVectorExtrusion();
  extrude->SetVector(0.0, 0.0, 1.0);
  extrude->CappingOn();
  vtkNew<vtkLinearSubdivisionFilter> subdivide;
  subdivide->SetInputData(testing::TriangulateAndClean(extrude));
  subdivide->SetNumberOfSubdivisions(3);
  subdivide->Update();
  vtkPolyData* input = subdivide->GetOutput();

  auto decimate = [&](bool center) {
    vtkNew<vtkTriangleCollapseDecimation> filter; // defaults: 8 levels down to 1%
    filter->SetInputData(input);
    filter->SetCenterOnInput(center);
    filter->Update();
    return vtkSmartPointer<vtkMultiBlockDataSet>(filter->GetHierarchy());
  };
  const auto plain = decimate(false);
  const auto centred = decimate(true);
  MESHLOD_REQUIRE_EQ(centred->GetNumberOfBlocks(), plain->GetNumberOfBlocks());
  int exactCentred = 0;
  for (unsigned int i = 1; i < centred->GetNumberOfBlocks(); ++i)
  {
    const SurfaceDistance before = MeasureSurfaceDistance(input, Level(plain, i));
    const SurfaceDistance after = MeasureSurfaceDistance(input, Level(centred, i));
    std::cerr << "  star prism, level " << i << " (" << Level(centred, i)->GetNumberOfPolys()
              << " triangles): Hausdorff " << before.HausdorffPercent() << "% -> "
              << after.HausdorffPercent() << "%\n";
    if (before.Hausdorff <= 1e-6 * before.Diagonal)
    {
      MESHLOD_CHECK_LE(after.Hausdorff, 1e-6 * after.Diagonal);
      const bool centrable = Level(centred, i)->GetNumberOfPolys() <=
        LevelCentering::LargestFraction * input->GetNumberOfPolys();
      exactCentred += centrable ? 1 : 0;
    }
  }
  MESHLOD_CHECK_GE(exactCentred, 4); // (the test covers levels that are centred)
}
} // namespace

int TestLevelCentering(int, char*[])
{
  vtkSmartPointer<vtkPolyData> metaballs =
    testing::MakeIsosurface(testing::Field::Metaballs, 70);
  std::cerr << "metaballs: " << metaballs->GetNumberOfPolys() << " triangles\n";
  TestCurvedSurface("vtkTriangleCollapseDecimation", metaballs, Decimate);
  TestCurvedSurface("vtkVertexClusterOctree", metaballs, Cluster);
  TestBoundaryAndFlatParts();
  TestFacetedSolid();
  return testing::Result();
}
