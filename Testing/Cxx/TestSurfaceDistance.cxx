// The quality yardstick against distances known in closed form.
#include "MeshLODSurfaceDistance.h"
#include "MeshLODTestCheck.h"
#include "MeshLODTestMeshes.h"

#include "vtkIdList.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkStaticCellLocator.h"

#include <cmath>
#include <vector>

namespace
{
using namespace meshlod;

vtkSmartPointer<vtkPolyData> Shifted(vtkPolyData* mesh, double dz, double scale = 1.0)
{
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->DeepCopy(mesh);
  for (vtkIdType i = 0; i < copy->GetNumberOfPoints(); ++i)
  {
    double p[3];
    copy->GetPoint(i, p);
    copy->GetPoints()->SetPoint(i, scale * p[0], scale * p[1], scale * p[2] + dz);
  }
  return copy;
}

void TestIdentical()
{
  vtkSmartPointer<vtkPolyData> sphere = testing::MakeIcosphere(3);
  const SurfaceDistance d = MeasureSurfaceDistance(sphere, sphere);
  MESHLOD_CHECK_LE(d.Hausdorff, 1e-12);
  MESHLOD_CHECK_LE(d.Rms, 1e-12);
  MESHLOD_CHECK_LE(std::abs(d.Diagonal - 2.0 * std::sqrt(3.0)), 0.2);
}

void TestParallelPlanes()
{
  // Two 4x4 squares 0.5 apart: every closest point is straight above or below.
  vtkSmartPointer<vtkPolyData> a = testing::MakeGrid(4, 4);
  vtkSmartPointer<vtkPolyData> b = Shifted(a, 0.5);
  const SurfaceDistance d = MeasureSurfaceDistance(a, b);
  MESHLOD_CHECK_LE(std::abs(d.Hausdorff - 0.5), 1e-12);
  MESHLOD_CHECK_LE(std::abs(d.Rms - 0.5), 1e-12);
  MESHLOD_CHECK_LE(std::abs(d.MaxAB - 0.5), 1e-12);
  MESHLOD_CHECK_LE(std::abs(d.RmsBA - 0.5), 1e-12);
  // Diagonal of a 4 x 4 x 0 box.
  MESHLOD_CHECK_LE(std::abs(d.HausdorffPercent() - 100.0 * 0.5 / std::sqrt(32.0)), 1e-9);
}

void TestConcentricSpheres()
{
  // A fine icosphere and a copy scaled by 1.1: distances lie between 0.1 minus the facet sag
  // and 0.1 plus it (facets of level 4 sag by less than 0.003).
  vtkSmartPointer<vtkPolyData> a = testing::MakeIcosphere(4);
  vtkSmartPointer<vtkPolyData> b = Shifted(a, 0.0, 1.1);
  const SurfaceDistance d = MeasureSurfaceDistance(a, b);
  MESHLOD_CHECK_GE(d.Hausdorff, 0.1 - 0.004);
  MESHLOD_CHECK_LE(d.Hausdorff, 0.1 + 0.004);
  MESHLOD_CHECK_GE(d.Rms, 0.1 - 0.004);
  MESHLOD_CHECK_LE(d.Rms, 0.1 + 0.004);
}

void TestOneSided()
{
  // A 2x2 patch inside a 4x4 square: every point of the patch is on the square (A->B = 0), but
  // the square's far corner is sqrt(2^2 + 2^2) from the patch.
  vtkSmartPointer<vtkPolyData> square = testing::MakeGrid(4, 4);
  vtkSmartPointer<vtkPolyData> patch = testing::MakeGrid(2, 2);
  const SurfaceDistance d = MeasureSurfaceDistance(patch, square);
  MESHLOD_CHECK_LE(d.MaxAB, 1e-12);
  MESHLOD_CHECK_LE(std::abs(d.MaxBA - std::sqrt(8.0)), 1e-9); // a vertex sample hits the corner
  MESHLOD_CHECK_GT(d.RmsBA, 0.5);
}

// A 4x4 square with a zero-area "spike" triangle (4,0)-(6,0)-(5,0) sticking out of one side.
vtkSmartPointer<vtkPolyData> GridWithSpike(double dz)
{
  vtkSmartPointer<vtkPolyData> grid = testing::MakeGrid(4, 4);
  vtkSmartPointer<vtkPolyData> mesh = Shifted(grid, dz);
  const vtkIdType a = mesh->GetPoints()->InsertNextPoint(6.0, 0.0, dz);
  const vtkIdType b = mesh->GetPoints()->InsertNextPoint(5.0, 0.0, dz);
  const vtkIdType spike[3] = { 4, a, b }; // point 4 is the grid's corner (4, 0)
  mesh->GetPolys()->InsertNextCell(3, spike);
  return mesh;
}

void TestDegenerateTriangles()
{
  // A surface of zero area: the square flattened onto the x axis, and a copy 0.5 above it.
  // Every closest point lies on a degenerate triangle's edge, 0.5 away.
  vtkSmartPointer<vtkPolyData> line = Shifted(testing::MakeGrid(4, 4), 0.0);
  for (vtkIdType i = 0; i < line->GetNumberOfPoints(); ++i)
  {
    double p[3];
    line->GetPoint(i, p);
    line->GetPoints()->SetPoint(i, p[0], 0.0, 0.0);
  }
  const SurfaceDistance flat = MeasureSurfaceDistance(line, Shifted(line, 0.5));
  MESHLOD_CHECK_LE(std::abs(flat.Hausdorff - 0.5), 1e-12);
  MESHLOD_CHECK_LE(std::abs(flat.Rms - 0.5), 1e-12);

  // A spike is found by its own edges: its tip (6, 0, 0) is 0.5 from the shifted spike, not
  // sqrt(2^2 + 0.5^2) from the shifted square's corner.
  const SurfaceDistance spiked = MeasureSurfaceDistance(GridWithSpike(0.0), GridWithSpike(0.5));
  MESHLOD_CHECK_LE(std::abs(spiked.Hausdorff - 0.5), 1e-12);
  MESHLOD_CHECK_LE(std::abs(spiked.MaxAB - 0.5), 1e-12);
}

// A flat 40 x 40 square (B) above a square with a narrow V-groove (A: half-width h, depth d,
// along x = x0, between B's grid lines). The point of B farthest from A is on the groove's
// centre line, h d / sqrt(h^2 + d^2) from its walls; a thin strip of B around that line is
// nearly as far, and B's vertices lie outside it. Random samples land near the line, not on
// it: the refinement climbs to it.
void TestNarrowFarthestSpot()
{
  const double x0 = 20.45, h = 0.2, d = 2.0, size = 40.0;
  std::vector<double> points;
  const double xs[5] = { 0.0, x0 - h, x0, x0 + h, size };
  const double zs[5] = { 0.0, 0.0, -d, 0.0, 0.0 };
  for (const double y : { 0.0, size })
  {
    for (int i = 0; i < 5; ++i)
    {
      points.insert(points.end(), { xs[i], y, zs[i] });
    }
  }
  std::vector<long long> strips;
  for (long long i = 0; i < 4; ++i)
  {
    strips.insert(strips.end(), { i, i + 1, i + 6, i, i + 6, i + 5 });
  }
  vtkSmartPointer<vtkPolyData> grooved = testing::MakePolyData(points, strips);
  vtkSmartPointer<vtkPolyData> flat = testing::MakeGrid(40, 40);
  const double farthest = h * d / std::sqrt(h * h + d * d);

  // Over 16 seeds (about 20 of the 2,000 samples land in the strip each time): the search ends
  // within 1/1024 of the triangle's width of the centre line, under 0.5% of the distance; the
  // samples alone fall short by a few percent on average.
  SurfaceDistanceOptions options;
  options.SamplesPerSurface = 2000;
  double sampledSum = 0.0;
  const int seeds = 16;
  for (int seed = 1; seed <= seeds; ++seed)
  {
    options.Seed = static_cast<std::uint64_t>(seed);
    options.RefinedSamples = 128;
    const SurfaceDistance refined = MeasureSurfaceDistance(grooved, flat, options);
    MESHLOD_CHECK_LE(std::abs(refined.MaxBA - farthest), 5e-3 * farthest);
    MESHLOD_CHECK_LE(std::abs(refined.MaxAB - d), 1e-12); // the groove's bottom, a vertex
    options.RefinedSamples = 0;
    const SurfaceDistance sampled = MeasureSurfaceDistance(grooved, flat, options);
    MESHLOD_CHECK_LE(sampled.MaxBA, refined.MaxBA);
    sampledSum += sampled.MaxBA;
  }
  MESHLOD_CHECK_LT(sampledSum / seeds, 0.98 * farthest);
}

void TestSameForEveryBackend()
{
  vtkSmartPointer<vtkPolyData> a = testing::MakeIsosurface(testing::Field::Metaballs, 40);
  vtkSmartPointer<vtkPolyData> b = testing::MakeIsosurface(testing::Field::Metaballs, 24);
  const std::string initial = vtkSMPTools::GetBackend();
  vtkSMPTools::SetBackend("Sequential");
  const SurfaceDistance sequential = MeasureSurfaceDistance(a, b);
  vtkSMPTools::SetBackend(initial.c_str());
  const SurfaceDistance parallel = MeasureSurfaceDistance(a, b);
  MESHLOD_CHECK_EQ(sequential.Hausdorff, parallel.Hausdorff);
  MESHLOD_CHECK_EQ(sequential.Rms, parallel.Rms);
  MESHLOD_CHECK_GT(sequential.Hausdorff, 0.0);
}
// BuildCellLocator pads cells in proportion to the data: on a sphere a millionth of a unit
// across, a small box meets a few cells, not all of them. (VTK's default absolute padding of
// 0.001 put every cell in every bucket: measuring the 327,680-triangle sphere below, when the
// yardstick searched such a locator, asked for tens of gigabytes and threw std::bad_alloc.)
// The yardstick's own search must measure that sphere too.
void TestTinySurface()
{
  vtkSmartPointer<vtkPolyData> sphere = testing::MakeIcosphere(4);
  testing::Scale(sphere, 1e-6);
  vtkSmartPointer<vtkStaticCellLocator> locator = BuildCellLocator(sphere);
  double box[6] = { -1e-7, 1e-7, -1e-7, 1e-7, 1e-6 - 1e-7, 1e-6 + 1e-7 };
  vtkNew<vtkIdList> cells;
  locator->FindCellsWithinBounds(box, cells);
  MESHLOD_CHECK_GT(cells->GetNumberOfIds(), 0);
  MESHLOD_CHECK_LT(cells->GetNumberOfIds(), sphere->GetNumberOfPolys() / 20);

  vtkSmartPointer<vtkPolyData> fine = testing::MakeIcosphere(7);
  testing::Scale(fine, 1e-6);
  vtkSmartPointer<vtkPolyData> larger = Shifted(fine, 0.0, 1.1);
  SurfaceDistanceOptions few; // the search trees are what this measures
  few.SamplesPerSurface = 2000;
  few.MaximumVertexSamples = 2000;
  const SurfaceDistance d = MeasureSurfaceDistance(fine, larger, few);
  MESHLOD_CHECK_GE(d.Hausdorff, (0.1 - 0.004) * 1e-6);
  MESHLOD_CHECK_LE(d.Hausdorff, (0.1 + 0.004) * 1e-6);
}
} // namespace

int TestSurfaceDistance(int, char*[])
{
  TestIdentical();
  TestParallelPlanes();
  TestConcentricSpheres();
  TestOneSided();
  TestDegenerateTriangles();
  TestNarrowFarthestSpot();
  TestSameForEveryBackend();
  TestTinySurface();
  return meshlod::testing::Result();
}
