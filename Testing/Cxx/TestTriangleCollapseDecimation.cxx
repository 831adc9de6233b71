// vtkTriangleCollapseDecimation end to end: hierarchies of closed and open isosurfaces and of
// tiny meshes, checked for topology, correspondence, errors, attributes, determinism and the
// handling of bad input and settings.
#include "vtkLODGeomorph.h"
#include "vtkTriangleCollapseDecimation.h"

#include "MeshLODEventCounter.h"
#include "MeshLODHierarchy.h"
#include "MeshLODHierarchyChecks.h"
#include "MeshLODSurfaceDistance.h"
#include "MeshLODTestCheck.h"
#include "MeshLODTestHierarchies.h"
#include "MeshLODTestMeshes.h"

#include "vtkAdaptiveSubdivisionFilter.h"
#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkCleanPolyData.h"
#include "vtkCylinderSource.h"
#include "vtkAppendPolyData.h"
#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIntArray.h"
#include "vtkLinearSubdivisionFilter.h"
#include "vtkLinearExtrusionFilter.h"
#include "vtkMath.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkParametricFunctionSource.h"
#include "vtkParametricBoy.h"
#include "vtkParametricMobius.h"
#include "vtkParametricTorus.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSOADataArrayTemplate.h"
#include "vtkQuadricDecimation.h"
#include "vtkSMPTools.h"
#include "vtkSphereSource.h"
#include "vtkSuperquadricSource.h"
#include "vtkTessellatedBoxSource.h"
#include "vtkTestErrorObserver.h"
#include "vtkTriangleFilter.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>
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

double Field(vtkPolyData* level, const char* name)
{
  vtkDataArray* a = level->GetFieldData()->GetArray(name);
  return a ? a->GetTuple1(0) : std::numeric_limits<double>::quiet_NaN();
}

// The edge length of equilateral triangles of the mesh's mean area.
double TypicalEdge(vtkPolyData* mesh)
{
  double area = 0.0;
  vtkIdType n;
  const vtkIdType* ids;
  for (vtkIdType c = 0; c < mesh->GetNumberOfPolys(); ++c)
  {
    mesh->GetPolys()->GetCellAtId(c, n, ids);
    double p[3][3], e1[3], e2[3], cross[3];
    for (int k = 0; k < 3; ++k)
    {
      mesh->GetPoint(ids[k], p[k]);
    }
    vtkMath::Subtract(p[1], p[0], e1);
    vtkMath::Subtract(p[2], p[0], e2);
    vtkMath::Cross(e1, e2, cross);
    area += 0.5 * vtkMath::Norm(cross);
  }
  return std::sqrt(4.0 * area / (std::sqrt(3.0) * std::max<vtkIdType>(1, mesh->GetNumberOfPolys())));
}

// Properties every hierarchy of a closed surface must have.
void CheckClosedHierarchy(vtkMultiBlockDataSet* h, const std::string& label)
{
  std::cerr << "checking " << label << "\n";
  MESHLOD_CHECK(CheckHierarchyLayout(h, true).empty());
  MESHLOD_CHECK_EQ(testing::CountCorrespondenceViolations(h), 0);
  const testing::MeshReport input = testing::InspectMesh(Level(h, 0));
  vtkIdType previous = Level(h, 0)->GetNumberOfPolys();
  for (unsigned int i = 1; i < h->GetNumberOfBlocks(); ++i)
  {
    vtkPolyData* level = Level(h, i);
    const testing::MeshReport r = testing::InspectMesh(level);
    MESHLOD_CHECK_LT(r.Triangles, previous);
    previous = r.Triangles;
    MESHLOD_CHECK_EQ(r.NonManifoldEdges, 0);
    MESHLOD_CHECK_EQ(r.NonManifoldVertices, 0);
    MESHLOD_CHECK_EQ(r.BoundaryEdges, 0);
    MESHLOD_CHECK_EQ(r.DegenerateTriangles, 0);
    MESHLOD_CHECK_EQ(r.DuplicateTriangles, 0);
    MESHLOD_CHECK(r.ConsistentlyOriented);
    MESHLOD_CHECK_EQ(r.EulerCharacteristic, input.EulerCharacteristic);
    MESHLOD_CHECK_EQ(testing::CountFlippedTriangles(Level(h, 0), level), 0);
    MESHLOD_CHECK_EQ(Field(level, names::LevelIndex), static_cast<double>(i));
    MESHLOD_CHECK_EQ(Field(level, names::NumberOfTriangles), static_cast<double>(r.Triangles));
  }
}

// Closed isosurface, every method, schedule and operator: manifold, closed, same genus, exact
// correspondence, counts at the requested levels, errors as measured.
void TestClosedIsosurface()
{
  vtkSmartPointer<vtkPolyData> surface = testing::MakeIsosurface(testing::Field::Metaballs, 40);
  const vtkIdType n = surface->GetNumberOfPolys();
  struct Variant
  {
    int Method, Schedule, Operator, CurvatureCost;
    const char* Label;
    // Measured on this mesh: 0.30, 0.39, 0.53, 1.55 and 0.36; about 1.3-2x margin.
    double MaxHausdorffPercentAt10;
  };
  const Variant variants[] = {
    { vtkTriangleCollapseDecimation::QUADRIC, vtkTriangleCollapseDecimation::GREEDY,
      vtkTriangleCollapseDecimation::TRIANGLES_AND_EDGES, vtkTriangleCollapseDecimation::WEIGHT,
      "quadric greedy", 0.5 },
    { vtkTriangleCollapseDecimation::QUADRIC, vtkTriangleCollapseDecimation::INDEPENDENT_SETS,
      vtkTriangleCollapseDecimation::TRIANGLES_AND_EDGES, vtkTriangleCollapseDecimation::WEIGHT,
      "quadric independent sets", 0.6 },
    { vtkTriangleCollapseDecimation::QUADRIC, vtkTriangleCollapseDecimation::INDEPENDENT_SETS,
      vtkTriangleCollapseDecimation::TRIANGLES, vtkTriangleCollapseDecimation::WEIGHT,
      "quadric triangles only", 0.7 },
    { vtkTriangleCollapseDecimation::CURVATURE, vtkTriangleCollapseDecimation::INDEPENDENT_SETS,
      vtkTriangleCollapseDecimation::TRIANGLES, vtkTriangleCollapseDecimation::WEIGHT,
      "curvature", 2.5 },
    { vtkTriangleCollapseDecimation::CURVATURE, vtkTriangleCollapseDecimation::GREEDY,
      vtkTriangleCollapseDecimation::TRIANGLES, vtkTriangleCollapseDecimation::FIT_DEVIATION,
      "curvature fit deviation", 0.6 },
  };
  std::vector<SurfaceDistance> at10Distances;
  for (const Variant& v : variants)
  {
    vtkNew<vtkTriangleCollapseDecimation> filter;
    filter->SetInputData(surface);
    filter->SetMethod(v.Method);
    filter->SetSchedule(v.Schedule);
    filter->SetOperator(v.Operator);
    filter->SetCurvatureCost(v.CurvatureCost);
    filter->ComputeLevelErrorOn();
    filter->Update();
    vtkMultiBlockDataSet* h = filter->GetHierarchy();
    MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 9u);
    MESHLOD_CHECK_EQ(filter->GetNumberOfLevelsProduced(), 9);
    CheckClosedHierarchy(h, v.Label);
    // Level 4 is 10% of the input (8 levels to 1%), level 8 is 1%; a collapse removes up to 4.
    const vtkIdType at10 = Level(h, 4)->GetNumberOfPolys();
    const vtkIdType at1 = Level(h, 8)->GetNumberOfPolys();
    MESHLOD_CHECK_LE(at10, static_cast<vtkIdType>(std::floor(0.1 * n + 1e-9)));
    MESHLOD_CHECK_GE(at10, static_cast<vtkIdType>(std::floor(0.1 * n)) - 4);
    MESHLOD_CHECK_LE(at1, static_cast<vtkIdType>(std::floor(0.01 * n + 1e-9)));
    MESHLOD_CHECK_GE(at1, static_cast<vtkIdType>(std::floor(0.01 * n)) - 4);

    // The reported measurement agrees with an independent, denser one.
    SurfaceDistanceOptions dense;
    dense.SamplesPerSurface = 100000;
    dense.Seed = 777;
    const SurfaceDistance d = MeasureSurfaceDistance(surface, Level(h, 4), dense);
    const double reported = Field(Level(h, 4), names::MeasuredHausdorff);
    MESHLOD_CHECK_LE(std::abs(d.Hausdorff - reported), 0.3 * reported);
    MESHLOD_CHECK_LE(std::abs(d.Rms - Field(Level(h, 4), names::MeasuredRMS)), 0.05 * d.Rms);
    std::cerr << "  " << v.Label << ": Hausdorff at 10% " << d.HausdorffPercent() << "% RMS "
              << d.RmsPercent() << "%\n";
    MESHLOD_CHECK_LE(d.HausdorffPercent(), v.MaxHausdorffPercentAt10);
    MESHLOD_CHECK_GT(Field(Level(h, 4), names::EstimatedError), 0.0);
    at10Distances.push_back(d);
  }
  // Ranked by the fitted surface's deviation the curvature method's error is a quarter to two
  // fifths of that of paper 000's weight (0.23x and 0.37x here; less on the benchmark meshes).
  const SurfaceDistance& weight = at10Distances[3];
  const SurfaceDistance& deviation = at10Distances[4];
  MESHLOD_CHECK_LE(deviation.Hausdorff, 0.35 * weight.Hausdorff);
  MESHLOD_CHECK_LE(deviation.Rms, 0.5 * weight.Rms);
}

// The torus keeps its hole: Euler characteristic 0 on every level.
void TestGenus()
{
  vtkNew<vtkTriangleCollapseDecimation> filter;
  filter->SetInputData(testing::MakeIsosurface(testing::Field::Torus, 40));
  filter->SetTargetReduction(0.995);
  filter->Update();
  vtkMultiBlockDataSet* h = filter->GetHierarchy();
  MESHLOD_CHECK_EQ(testing::InspectMesh(Level(h, 0)).EulerCharacteristic, 0);
  CheckClosedHierarchy(h, "torus");
}

// An open surface: the boundary stays on the input's boundary, within a small distance.
void TestOpenSurface(int method)
{
  vtkSmartPointer<vtkPolyData> sheet = testing::MakeIsosurface(testing::Field::Wavelet, 41);
  vtkNew<vtkTriangleCollapseDecimation> filter;
  filter->SetInputData(sheet);
  filter->SetMethod(method);
  filter->Update();
  std::cerr << "open surface, " << filter->GetMethodAsString() << " method\n";
  vtkMultiBlockDataSet* h = filter->GetHierarchy();
  MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 9u);
  MESHLOD_CHECK_EQ(testing::CountCorrespondenceViolations(h), 0);
  const double diagonal = sheet->GetLength();
  for (unsigned int i = 1; i < h->GetNumberOfBlocks(); ++i)
  {
    const testing::MeshReport r = testing::InspectMesh(Level(h, i));
    MESHLOD_CHECK_EQ(r.NonManifoldEdges, 0);
    MESHLOD_CHECK_EQ(r.NonManifoldVertices, 0);
    MESHLOD_CHECK_EQ(r.DegenerateTriangles, 0);
    MESHLOD_CHECK_GT(r.BoundaryEdges, 0);
    // Boundary vertices stay within a fraction of the level's typical edge length of the
    // input boundary. Measured, quadric method: up to 0.23 of it at the coarsest level, far less
    // before. The curvature method collapses whole triangles, which cut the boundary's corners:
    // up to 0.27 down to 3% of the input (level 6), 0.25 and 0.58 at the two coarsest levels
    // (about 100 and 60 triangles), which are left out. (Ranked by paper 000's weight, which
    // does not see the boundary: up to 0.46, and 0.6 to 1.6.)
    const double deviation = testing::BoundaryDeviation(sheet, Level(h, i));
    std::cerr << "  boundary deviation level " << i << ": " << deviation / TypicalEdge(Level(h, i))
              << " edge lengths\n";
    if (method == vtkTriangleCollapseDecimation::QUADRIC)
    {
      MESHLOD_CHECK_LE(deviation, 0.35 * TypicalEdge(Level(h, i)));
      MESHLOD_CHECK_LE(deviation, 0.05 * diagonal);
    }
    else if (i <= 6)
    {
      MESHLOD_CHECK_LE(deviation, 0.45 * TypicalEdge(Level(h, i)));
      MESHLOD_CHECK_LE(deviation, 0.05 * diagonal);
    }
  }
}

// ... with either method.
void TestOpenSurface()
{
  for (const int method :
    { vtkTriangleCollapseDecimation::QUADRIC, vtkTriangleCollapseDecimation::CURVATURE })
  {
    TestOpenSurface(method);
  }
}


// Point data: floating arrays interpolated, normals unit length, integer arrays keep values
// that exist in the input.
void TestPointData()
{
  vtkSmartPointer<vtkPolyData> surface =
    testing::MakeIsosurface(testing::Field::Metaballs, 32, true, true);
  vtkNew<vtkIntArray> side;
  side->SetName("Side");
  for (vtkIdType p = 0; p < surface->GetNumberOfPoints(); ++p)
  {
    side->InsertNextValue(surface->GetPoint(p)[0] < 0.0 ? 7 : 9);
  }
  surface->GetPointData()->AddArray(side);
  // A constant far from 0 (a date, a map coordinate) must come through exactly: the weights are
  // stored in single precision, which put it off by up to 108 in 1e9.
  vtkNew<vtkDoubleArray> constant;
  constant->SetName("Constant");
  constant->SetNumberOfTuples(surface->GetNumberOfPoints());
  constant->Fill(1e9 + 0.25);
  surface->GetPointData()->AddArray(constant);
  // Field data (metadata) is passed to every level, but for a name of the levels' own: an input
  // that is a measured level must not lend its MeasuredHausdorff to levels not measured.
  vtkNew<vtkIntArray> run, clash;
  vtkNew<vtkDoubleArray> measured;
  run->SetName("RunNumber");
  run->InsertNextValue(42);
  clash->SetName(names::LevelIndex);
  clash->InsertNextValue(-5);
  measured->SetName(names::MeasuredHausdorff);
  measured->InsertNextValue(0.125);
  surface->GetFieldData()->AddArray(run);
  surface->GetFieldData()->AddArray(clash);
  surface->GetFieldData()->AddArray(measured);
  vtkNew<vtkTriangleCollapseDecimation> filter;
  filter->SetInputData(surface);
  filter->SetNumberOfLevels(3);
  filter->Update();
  vtkMultiBlockDataSet* h = filter->GetHierarchy();
  MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 4u);
  double range[2];
  surface->GetPointData()->GetScalars()->GetRange(range);
  for (unsigned int i = 0; i < h->GetNumberOfBlocks(); ++i)
  {
    vtkPolyData* level = Level(h, i);
    vtkDataArray* passed = level->GetFieldData()->GetArray("RunNumber");
    MESHLOD_CHECK(passed != nullptr && passed->GetTuple1(0) == 42.0);
    MESHLOD_CHECK_EQ(Field(level, names::LevelIndex), static_cast<double>(i));
    MESHLOD_CHECK(level->GetFieldData()->GetArray(names::MeasuredHausdorff) == nullptr);
    vtkPointData* pd = level->GetPointData();
    MESHLOD_CHECK(pd->GetNormals() != nullptr);
    MESHLOD_CHECK(pd->GetScalars() != nullptr);
    MESHLOD_CHECK(pd->GetArray("Side") != nullptr);
    if (!pd->GetNormals() || !pd->GetScalars() || !pd->GetArray("Side"))
    {
      continue;
    }
    MESHLOD_CHECK_EQ(pd->GetNormals()->GetNumberOfTuples(), level->GetNumberOfPoints());
    for (vtkIdType p = 0; p < level->GetNumberOfPoints(); ++p)
    {
      double normal[3];
      pd->GetNormals()->GetTuple(p, normal);
      MESHLOD_CHECK_LE(std::abs(vtkMath::Norm(normal) - 1.0), 1e-5);
      const double s = pd->GetScalars()->GetTuple1(p);
      MESHLOD_CHECK(s >= range[0] - 1e-6 && s <= range[1] + 1e-6);
      const double label = pd->GetArray("Side")->GetTuple1(p);
      MESHLOD_CHECK(label == 7.0 || label == 9.0);
      MESHLOD_CHECK(pd->GetArray("Constant") && pd->GetArray("Constant")->GetTuple1(p) == 1e9 + 0.25);
    }
  }
}

// One triangle collapse on an icosphere removes exactly 4 triangles and 2 vertices; the three
// merged points share rank 0 and one target, every other point keeps its place.
void TestSingleCollapse()
{
  vtkNew<vtkTriangleCollapseDecimation> filter;
  filter->SetInputData(testing::MakeIcosphere(1)); // 80 triangles, 42 points
  filter->SetOperatorToTriangles();
  filter->AddLevelReduction(0.05); // 76 triangles
  filter->Update();
  vtkMultiBlockDataSet* h = filter->GetHierarchy();
  MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 2u);
  MESHLOD_CHECK_EQ(Level(h, 1)->GetNumberOfPolys(), 76);
  MESHLOD_CHECK_EQ(Level(h, 1)->GetNumberOfPoints(), 40);
  vtkDataArray* rank = Level(h, 0)->GetPointData()->GetArray(names::CollapseRank);
  vtkDataArray* target = Level(h, 0)->GetPointData()->GetArray(names::MorphTargetId);
  int moving = 0;
  std::set<double> targets;
  for (vtkIdType p = 0; p < 42; ++p)
  {
    if (rank->GetTuple1(p) == 0.0)
    {
      ++moving;
      targets.insert(target->GetTuple1(p));
    }
    else
    {
      MESHLOD_CHECK_EQ(rank->GetTuple1(p), -1.0);
    }
  }
  MESHLOD_CHECK_EQ(moving, 3);
  MESHLOD_CHECK_EQ(targets.size(), 1u);
  MESHLOD_CHECK_EQ(testing::CountCorrespondenceViolations(h), 0);
}

// Marching cubes puts several points at one place where the surface passes through a sample,
// with zero-area triangles between them. Here vertex 0 of an icosphere becomes three
// coincident points, one per third of its fan, joined by three triangles with two coincident
// corners and one with three: all four must collapse (none may lock the collapses around it).
void TestCoincidentPoints()
{
  vtkSmartPointer<vtkPolyData> sphere = testing::MakeIcosphere(2);
  std::vector<double> points;
  for (vtkIdType p = 0; p < sphere->GetNumberOfPoints(); ++p)
  {
    double x[3];
    sphere->GetPoint(p, x);
    points.insert(points.end(), x, x + 3);
  }
  std::vector<long long> triangles;
  std::vector<std::array<long long, 3>> fan; // triangles (0, a, b)
  for (const testing::TriangleIds& t : testing::Triangles(sphere))
  {
    const int c = t[0] == 0 ? 0 : (t[1] == 0 ? 1 : (t[2] == 0 ? 2 : -1));
    if (c < 0)
    {
      triangles.insert(triangles.end(), t.begin(), t.end());
      continue;
    }
    fan.push_back({ 0, t[(c + 1) % 3], t[(c + 2) % 3] });
  }
  // Order the fan: each triangle's b is the next one's a.
  for (std::size_t i = 1; i < fan.size(); ++i)
  {
    for (std::size_t j = i; j < fan.size(); ++j)
    {
      if (fan[j][1] == fan[i - 1][2])
      {
        std::swap(fan[i], fan[j]);
      }
    }
  }
  const long long centre[3] = { 0, static_cast<long long>(points.size() / 3),
    static_cast<long long>(points.size() / 3 + 1) };
  points.insert(points.end(), points.begin(), points.begin() + 3);
  points.insert(points.end(), points.begin(), points.begin() + 3);
  const std::size_t sectors = 3, count = fan.size();
  for (std::size_t i = 0; i < count; ++i)
  {
    const long long c = centre[i * sectors / count];
    triangles.insert(triangles.end(), { c, fan[i][1], fan[i][2] });
  }
  for (std::size_t k = 0; k < sectors; ++k)
  {
    // Between sector k and k + 1, at the fan vertex where they meet.
    const std::size_t first = ((k + 1) * count + sectors - 1) / sectors % count;
    triangles.insert(triangles.end(), { centre[k], fan[first][1], centre[(k + 1) % sectors] });
  }
  triangles.insert(triangles.end(), { centre[0], centre[1], centre[2] });
  vtkSmartPointer<vtkPolyData> mesh = testing::MakePolyData(points, triangles);
  const testing::MeshReport input = testing::InspectMesh(mesh);
  MESHLOD_CHECK_EQ(input.DegenerateTriangles, 4);
  MESHLOD_CHECK_EQ(input.NonManifoldEdges, 0);
  MESHLOD_CHECK_EQ(input.NonManifoldVertices, 0);
  MESHLOD_CHECK(input.ConsistentlyOriented);
  MESHLOD_CHECK_EQ(input.EulerCharacteristic, 2);

  vtkNew<vtkTriangleCollapseDecimation> filter;
  filter->SetInputData(mesh);
  filter->AddLevelReduction(0.1);
  filter->AddLevelReduction(0.5);
  filter->Update();
  vtkMultiBlockDataSet* h = filter->GetHierarchy();
  MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 3u);
  for (unsigned int i = 1; i < h->GetNumberOfBlocks(); ++i)
  {
    const testing::MeshReport r = testing::InspectMesh(Level(h, i));
    MESHLOD_CHECK_EQ(r.DegenerateTriangles, 0);
    MESHLOD_CHECK_EQ(r.NonManifoldEdges, 0);
    MESHLOD_CHECK_EQ(r.EulerCharacteristic, 2);
  }
}

// A closed mesh whose points are all at one place (every triangle has zero area), large enough
// for the greedy order's parallel rounds: the grid has no size to cut, and the run must still
// end, with valid levels.
void TestAllPointsCoincident()
{
  vtkSmartPointer<vtkPolyData> sphere = testing::MakeIcosphere(5); // 20480 triangles
  for (vtkIdType p = 0; p < sphere->GetNumberOfPoints(); ++p)
  {
    sphere->GetPoints()->SetPoint(p, 1.0, 2.0, 3.0);
  }
  for (const bool partitioned : { true, false })
  {
    vtkNew<vtkTriangleCollapseDecimation> filter;
    filter->SetInputData(sphere);
    filter->SetPartitionedGreedy(partitioned);
    filter->SetNumberOfLevels(2);
    filter->Update();
    vtkMultiBlockDataSet* h = filter->GetHierarchy();
    MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 3u);
    MESHLOD_CHECK_EQ(testing::CountCorrespondenceViolations(h), 0);
    const testing::MeshReport r = testing::InspectMesh(Level(h, h->GetNumberOfBlocks() - 1));
    MESHLOD_CHECK_LE(r.Triangles, 205);
    MESHLOD_CHECK_EQ(r.NonManifoldEdges, 0);
    MESHLOD_CHECK_EQ(r.EulerCharacteristic, 2);
  }
}

// Same output for the sequential backend and the default (threaded) one.
void TestThreadIndependence()
{
  vtkSmartPointer<vtkPolyData> surface = testing::MakeIsosurface(testing::Field::Gyroid, 40);
  const std::string initial = vtkSMPTools::GetBackend();
  for (const int schedule :
    { vtkTriangleCollapseDecimation::GREEDY, vtkTriangleCollapseDecimation::INDEPENDENT_SETS })
  {
    vtkSmartPointer<vtkMultiBlockDataSet> runs[2];
    for (int run = 0; run < 2; ++run)
    {
      vtkSMPTools::SetBackend(run == 0 ? "Sequential" : initial.c_str());
      vtkNew<vtkTriangleCollapseDecimation> filter;
      filter->SetInputData(surface);
      filter->SetSchedule(schedule);
      filter->Update();
      runs[run] = filter->GetHierarchy();
    }
    MESHLOD_CHECK_EQ(testing::CountDifferingLevels(runs[0], runs[1]), 0);
  }
  vtkSMPTools::SetBackend(initial.c_str());
}

// The greedy schedule in parallel rounds over spatial cells, on a mesh large enough for many
// cells and rounds, with the quadric method and with the curvature method (whose fits and lazy
// re-weighting reach two rings beyond a collapse): the same hierarchy on one thread and on
// several, valid meshes landing on the level counts, an error close to the strictly serial
// greedy order's (and levels that differ from it: the rounds did run).
void TestPartitionedGreedy(int method)
{
  vtkSmartPointer<vtkPolyData> surface = testing::MakeIsosurface(
    testing::Field::Gyroid, testing::ResolutionForTriangles(testing::Field::Gyroid, 120000));
  const vtkIdType n = surface->GetNumberOfPolys();
  const std::string initial = vtkSMPTools::GetBackend();
  vtkSmartPointer<vtkMultiBlockDataSet> runs[3];
  for (int run = 0; run < 3; ++run)
  {
    vtkSMPTools::SetBackend(run == 0 ? "Sequential" : initial.c_str());
    vtkNew<vtkTriangleCollapseDecimation> filter;
    filter->SetInputData(surface);
    filter->SetMethod(method);
    filter->SetPartitionedGreedy(run < 2); // run 2: strictly serial
    filter->Update();
    runs[run] = filter->GetHierarchy();
    if (run == 0)
    {
      std::cerr << "partitioned greedy on " << n << " triangles, " << filter->GetMethodAsString()
                << " method\n";
    }
  }
  vtkSMPTools::SetBackend(initial.c_str());
  MESHLOD_CHECK_EQ(runs[0]->GetNumberOfBlocks(), 9u);
  MESHLOD_CHECK_EQ(runs[1]->GetNumberOfBlocks(), 9u);
  MESHLOD_CHECK_EQ(testing::CountCorrespondenceViolations(runs[0]), 0);
  MESHLOD_CHECK(!testing::SameMesh(Level(runs[0], 4), Level(runs[2], 4)));
  MESHLOD_CHECK_EQ(testing::CountDifferingLevels(runs[0], runs[1]), 0);
  const testing::MeshReport input = testing::InspectMesh(Level(runs[0], 0));
  for (unsigned int i = 1; i < runs[0]->GetNumberOfBlocks(); ++i)
  {
    vtkPolyData* level = Level(runs[0], i);
    const testing::MeshReport r = testing::InspectMesh(level);
    // The same counts as the serial order: each level lands on its target (a collapse removes
    // up to 4 triangles, so up to 3 below it).
    const vtkIdType serial = Level(runs[2], i)->GetNumberOfPolys();
    MESHLOD_CHECK_LE(std::llabs(r.Triangles - serial), 3);
    MESHLOD_CHECK_EQ(r.NonManifoldEdges, 0);
    MESHLOD_CHECK_EQ(r.NonManifoldVertices, 0);
    MESHLOD_CHECK_EQ(r.DegenerateTriangles, 0);
    MESHLOD_CHECK_EQ(r.DuplicateTriangles, 0);
    MESHLOD_CHECK(r.ConsistentlyOriented);
    MESHLOD_CHECK_EQ(r.EulerCharacteristic, input.EulerCharacteristic);
    MESHLOD_CHECK_EQ(testing::CountFlippedTriangles(Level(runs[0], 0), level), 0);
  }
  // Error at 10% and 1% against the serial order's (measured: the quadric method within 4% RMS
  // and 1.4x Hausdorff; the curvature method within 2% RMS, its Hausdorff distance lower).
  for (const unsigned int i : { 4u, 8u })
  {
    const SurfaceDistance parallel = MeasureSurfaceDistance(surface, Level(runs[0], i));
    const SurfaceDistance serial = MeasureSurfaceDistance(surface, Level(runs[2], i));
    std::cerr << "  level " << i << ": RMS " << parallel.RmsPercent() << "% (serial "
              << serial.RmsPercent() << "%), Hausdorff " << parallel.HausdorffPercent()
              << "% (serial " << serial.HausdorffPercent() << "%)\n";
    MESHLOD_CHECK_LE(parallel.Rms, 1.1 * serial.Rms);
    MESHLOD_CHECK_LE(parallel.Hausdorff, 1.5 * serial.Hausdorff);
  }
}

// Points that no collapse moves keep their coordinates to the last bit on every level (the
// engine works about the bounding box's centre, and the way back rounded: on these two
// spheres, off centre, 20 points of CollapseRank -1 had a MorphTarget 1e-16 away from them).
void TestUnmovedPointsExact()
{
  vtkNew<vtkSphereSource> large;
  large->SetThetaResolution(40);
  large->SetPhiResolution(40);
  vtkNew<vtkSphereSource> small;
  small->SetCenter(3.0, 0.0, 0.0);
  small->SetRadius(0.05);
  vtkNew<vtkAppendPolyData> both;
  both->AddInputConnection(large->GetOutputPort());
  both->AddInputConnection(small->GetOutputPort());
  vtkNew<vtkTriangleCollapseDecimation> filter;
  filter->SetInputConnection(both->GetOutputPort());
  filter->Update();
  MESHLOD_CHECK_EQ(testing::CountCorrespondenceViolations(filter->GetHierarchy()), 0);
}

// MaximumError stops early: fewer levels (with a warning), every vertex within the bound.
void TestMaximumError()
{
  vtkSmartPointer<vtkPolyData> surface = testing::MakeIsosurface(testing::Field::Sphere, 40);
  const double bound = 1e-3 * surface->GetLength();
  vtkNew<vtkTriangleCollapseDecimation> filter;
  vtkNew<vtkTest::ErrorObserver> observer;
  filter->AddObserver(vtkCommand::WarningEvent, observer);
  filter->SetInputData(surface);
  filter->SetMaximumError(bound);
  filter->Update();
  vtkMultiBlockDataSet* h = filter->GetHierarchy();
  MESHLOD_CHECK_LT(h->GetNumberOfBlocks(), 9u);
  MESHLOD_CHECK_GE(h->GetNumberOfBlocks(), 2u);
  MESHLOD_CHECK(observer->GetWarning());
  vtkPolyData* last = Level(h, h->GetNumberOfBlocks() - 1);
  MESHLOD_CHECK_LE(Field(last, names::EstimatedError), bound);
  MESHLOD_CHECK_LT(filter->GetActualReduction(), 0.99);
  MESHLOD_CHECK(observer->GetWarningMessage().find("(MaximumError reached)") != std::string::npos);

  // A bound that stops nothing is not named as the reason: a 12 x 12 UV sphere runs out of
  // legal collapses at 4 triangles, short of its 1% target, with or without the bound (and, one
  // piece, it is not told to turn PreserveTopology off).
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(12);
  sphere->SetPhiResolution(12);
  filter->SetInputConnection(sphere->GetOutputPort());
  for (const double limit : { 0.0, 1e9 })
  {
    observer->Clear();
    filter->SetMaximumError(limit);
    filter->Update();
    MESHLOD_CHECK(
      observer->GetWarningMessage().find("(no legal collapse left)") != std::string::npos);
  }
}

// More level targets than a small mesh has collapses to spread them over: a collapse that passes
// several targets gives one level for all of them (it used to give one copy per target: 371
// levels for 1000 on a 448-triangle sphere, 149 of them equal to the one before), without a
// warning, and the coarsest level still reaches the coarsest target.
void TestCrowdedTargets()
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(16);
  sphere->SetPhiResolution(16);
  sphere->Update();
  vtkNew<vtkTriangleCollapseDecimation> filter;
  vtkNew<vtkTest::ErrorObserver> observer;
  filter->AddObserver(vtkCommand::WarningEvent, observer);
  filter->SetInputData(sphere->GetOutput());
  filter->SetNumberOfLevels(1000);
  filter->Update();
  vtkMultiBlockDataSet* h = filter->GetHierarchy();
  MESHLOD_CHECK_GT(h->GetNumberOfBlocks(), 100u);
  MESHLOD_CHECK_LT(h->GetNumberOfBlocks(), 1001u);
  for (unsigned int i = 1; i < h->GetNumberOfBlocks(); ++i)
  {
    MESHLOD_CHECK_LT(Level(h, i)->GetNumberOfPolys(), Level(h, i - 1)->GetNumberOfPolys());
  }
  MESHLOD_CHECK_LE(Level(h, h->GetNumberOfBlocks() - 1)->GetNumberOfPolys(), 448 / 100 + 3);
  MESHLOD_CHECK(!observer->GetWarning());
  MESHLOD_CHECK_EQ(testing::CountCorrespondenceViolations(h), 0);
}

// Bad input and settings: clear errors, empty outputs, no crash; abort honoured.
void TestErrorsAndAbort()
{
  vtkNew<vtkTest::ErrorObserver> observer;
  {
    // Empty input: one empty level (a vtkLODGeomorph downstream then gives an empty mesh).
    vtkNew<vtkTriangleCollapseDecimation> filter;
    vtkNew<vtkPolyData> empty;
    filter->SetInputData(empty);
    filter->Update();
    MESHLOD_CHECK_EQ(filter->GetHierarchy()->GetNumberOfBlocks(), 1u);
    MESHLOD_CHECK_EQ(Level(filter->GetHierarchy(), 0)->GetNumberOfPoints(), 0);
  }
  {
    // TargetReduction 0 asks for no level but level 0 (the missed-target check used to read
    // the last of no targets).
    vtkNew<vtkTriangleCollapseDecimation> filter;
    filter->AddObserver(vtkCommand::ErrorEvent, observer);
    filter->AddObserver(vtkCommand::WarningEvent, observer);
    filter->SetInputData(testing::MakeIcosphere(2));
    filter->SetTargetReduction(0.0);
    filter->Update();
    MESHLOD_CHECK_EQ(filter->GetHierarchy()->GetNumberOfBlocks(), 1u);
    MESHLOD_CHECK(!observer->GetError());
    MESHLOD_CHECK(!observer->GetWarning());
    observer->Clear();
  }
  {
    // NaN settings pass vtkSetClampMacro; they are an error naming the setting.
    vtkNew<vtkTriangleCollapseDecimation> filter;
    filter->AddObserver(vtkCommand::ErrorEvent, observer);
    filter->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, observer);
    filter->SetInputData(testing::MakeIcosphere(2));
    filter->SetTargetReduction(std::numeric_limits<double>::quiet_NaN());
    filter->Update();
    MESHLOD_CHECK(observer->GetErrorMessage().find("TargetReduction is NaN") != std::string::npos);
    MESHLOD_CHECK_EQ(filter->GetHierarchy()->GetNumberOfBlocks(), 0u);
    observer->Clear();
  }
  for (const double scale : { 1e35, 1e-35 })
  {
    // Coordinates whose squared areas the collapse costs cannot hold: an error (scaled by
    // 1e200, a sphere got another collapse order and a measured error of 1e-51 of its own).
    vtkSmartPointer<vtkPolyData> scaled = testing::MakeIcosphere(2);
    testing::Scale(scaled, scale);
    vtkNew<vtkTriangleCollapseDecimation> filter;
    filter->AddObserver(vtkCommand::ErrorEvent, observer);
    filter->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, observer);
    filter->SetInputData(scaled);
    filter->Update();
    MESHLOD_CHECK(observer->GetErrorMessage().find("bounding-box diagonal") != std::string::npos);
    MESHLOD_CHECK_EQ(filter->GetHierarchy()->GetNumberOfBlocks(), 0u);
    observer->Clear();
  }
  {
    // An input array named like a hierarchy array is replaced on the levels: a warning says so.
    vtkSmartPointer<vtkPolyData> mesh = testing::MakeIcosphere(2);
    vtkNew<vtkIntArray> mine;
    mine->SetName(names::MorphTargetId);
    mine->SetNumberOfTuples(mesh->GetNumberOfPoints());
    mine->Fill(7);
    mesh->GetPointData()->AddArray(mine);
    vtkNew<vtkTest::ErrorObserver> warnings;
    vtkNew<vtkTriangleCollapseDecimation> filter;
    filter->AddObserver(vtkCommand::WarningEvent, warnings);
    filter->SetInputData(mesh);
    filter->Update();
    MESHLOD_CHECK(warnings->GetWarningMessage().find("\"MorphTargetId\" is replaced") !=
      std::string::npos);
  }
  {
    vtkNew<vtkTriangleCollapseDecimation> filter;
    filter->AddObserver(vtkCommand::ErrorEvent, observer);
    filter->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, observer);
    vtkSmartPointer<vtkPolyData> mesh = testing::MakeOctahedron();
    mesh->GetPoints()->SetPoint(2, std::numeric_limits<double>::quiet_NaN(), 0, 0);
    filter->SetInputData(mesh);
    filter->Update();
    MESHLOD_CHECK(observer->GetError());
    MESHLOD_CHECK(observer->GetErrorMessage().find("NaN") != std::string::npos);
    MESHLOD_CHECK_EQ(filter->GetHierarchy()->GetNumberOfBlocks(), 0u);
  }
  {
    // A NaN point that no triangle uses is dropped like any unused point: every level is the
    // same as without it.
    observer->Clear();
    const auto run = [&](vtkPolyData* input) {
      vtkNew<vtkTriangleCollapseDecimation> filter;
      filter->AddObserver(vtkCommand::ErrorEvent, observer);
      filter->SetInputData(input);
      filter->Update();
      MESHLOD_CHECK_GT(filter->GetHierarchy()->GetNumberOfBlocks(), 4u);
      return vtkSmartPointer<vtkMultiBlockDataSet>(filter->GetHierarchy());
    };
    MESHLOD_CHECK_EQ(testing::CountLevelsChangedByUnusedNaNPoint(run), 0);
    MESHLOD_CHECK(!observer->GetError());
  }
  {
    observer->Clear();
    vtkNew<vtkTriangleCollapseDecimation> filter;
    filter->AddObserver(vtkCommand::ErrorEvent, observer);
    filter->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, observer);
    filter->SetInputData(testing::MakeIcosphere(2));
    filter->SetMethodToCurvature();
    filter->SetCurvatureWeight(0.5);
    filter->SetAngleWeight(0.5);
    filter->SetValenceWeight(0.5);
    filter->Update();
    MESHLOD_CHECK(observer->GetError());
    MESHLOD_CHECK(observer->GetErrorMessage().find("must be 1") != std::string::npos);
  }
  {
    observer->Clear();
    vtkNew<vtkTriangleCollapseDecimation> filter;
    filter->AddObserver(vtkCommand::ErrorEvent, observer);
    filter->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, observer);
    filter->SetInputData(testing::MakeIcosphere(2));
    filter->AddLevelReduction(0.5);
    filter->AddLevelReduction(0.4);
    filter->Update();
    MESHLOD_CHECK(observer->GetError());
    MESHLOD_CHECK(observer->GetErrorMessage().find("increase") != std::string::npos);
  }
  {
    // A last level short of its target is reported even though the run emits the mesh it
    // reached as a level (the level count is then complete): a torus whose seam stays open
    // (its texture coordinates wrap), triangle collapses only.
    vtkNew<vtkSuperquadricSource> torus;
    torus->SetThetaResolution(32);
    torus->SetPhiResolution(32);
    torus->ToroidalOn();
    vtkNew<vtkTriangleFilter> triangles;
    triangles->SetInputConnection(torus->GetOutputPort());
    vtkNew<vtkTest::ErrorObserver> warnings;
    vtkNew<vtkTriangleCollapseDecimation> filter;
    filter->AddObserver(vtkCommand::WarningEvent, warnings);
    filter->SetInputConnection(triangles->GetOutputPort());
    filter->SetOperatorToTriangles();
    filter->SetNumberOfLevels(4);
    filter->Update();
    const vtkIdType coarsest =
      Level(filter->GetHierarchy(), filter->GetHierarchy()->GetNumberOfBlocks() - 1)
        ->GetNumberOfPolys();
    MESHLOD_CHECK_GT(coarsest, 2048 / 100 + 3);
    MESHLOD_CHECK(warnings->GetWarningMessage().find("short of its target of 20") !=
      std::string::npos);
  }
  {
    // Abort at the first progress report: the output stays empty, no error.
    observer->Clear();
    vtkNew<vtkTriangleCollapseDecimation> filter;
    filter->AddObserver(vtkCommand::ErrorEvent, observer);
    int reports = 0;
    vtkNew<vtkCallbackCommand> abort;
    abort->SetClientData(&reports);
    abort->SetCallback([](vtkObject* caller, unsigned long, void* data, void*) {
      ++*static_cast<int*>(data);
      static_cast<vtkAlgorithm*>(caller)->AbortExecuteOn();
    });
    filter->AddObserver(vtkCommand::ProgressEvent, abort);
    filter->SetInputData(testing::MakeIsosurface(testing::Field::Sphere, 32));
    filter->Update();
    MESHLOD_CHECK_GT(reports, 0);
    MESHLOD_CHECK_EQ(filter->GetHierarchy()->GetNumberOfBlocks(), 0u);
    MESHLOD_CHECK(!observer->GetError());
  }
  {
    // Non-manifold input: the pinched vertex is locked and never moves.
    vtkNew<vtkTriangleCollapseDecimation> filter;
    vtkSmartPointer<vtkPolyData> bowTie = testing::MakeBowTie();
    filter->SetInputData(bowTie);
    filter->SetTargetReduction(0.5);
    filter->SetNumberOfLevels(1);
    filter->Update();
    vtkMultiBlockDataSet* h = filter->GetHierarchy();
    MESHLOD_CHECK_GE(h->GetNumberOfBlocks(), 1u);
    vtkPolyData* last = Level(h, h->GetNumberOfBlocks() - 1);
    bool pinchKept = false;
    for (vtkIdType p = 0; p < last->GetNumberOfPoints(); ++p)
    {
      double x[3];
      last->GetPoint(p, x);
      pinchKept = pinchKept || (x[0] == 0.0 && x[1] == 0.0 && x[2] == 0.0);
    }
    MESHLOD_CHECK(pinchKept);
  }
  std::ostringstream print;
  vtkNew<vtkTriangleCollapseDecimation> filter;
  filter->Print(print);
  MESHLOD_CHECK(print.str().find("TriangleCostFactor: 1.5") != std::string::npos);
  MESHLOD_CHECK(print.str().find("Placement: Regularized") != std::string::npos);
}
} // namespace

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
  MESHLOD_CHECK(coarse != nullptr);
  if (!coarse)
  {
    return;
  }
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
    MESHLOD_CHECK(coarse != nullptr);
    if (!coarse)
    {
      return;
    }
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
  MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 3u);
  if (h->GetNumberOfBlocks() != 3)
  {
    return;
  }
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
  MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 4u);
  if (h->GetNumberOfBlocks() != 4)
  {
    return;
  }
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
  MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 4u);
  if (h->GetNumberOfBlocks() != 4)
  {
    return;
  }
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
  MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 3u);
  if (h->GetNumberOfBlocks() != 3)
  {
    return;
  }
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
  MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 3u);
  if (h->GetNumberOfBlocks() != 3)
  {
    return;
  }
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
    MESHLOD_CHECK(coarse != nullptr);
    if (!coarse)
    {
      return;
    }
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

int TestTriangleCollapseDecimation(int, char*[])
{
  TestSingleCollapse();
  TestCoincidentPoints();
  TestAllPointsCoincident();
  TestClosedIsosurface();
  TestGenus();
  TestOpenSurface();
  TestFlatGrid();
  TestFacetedCylinder();
  TestFlatFacedBox();
  TestParametricSeam();
  TestHighValenceFan();
  TestFlatFanInRing();
  TestHighValenceFanIndependentSets();
  TestIndependentSetsStall();
  TestFarFromOrigin();
  TestNoisySurface();
  TestSurfaceWithHoles();
  TestNoisySurfaceCurvature(vtkTriangleCollapseDecimation::WEIGHT, 4.0, 4.0);
  TestCurvatureReadsInputPoints();
  TestNoisySurfaceCurvature(vtkTriangleCollapseDecimation::FIT_DEVIATION, 5.0, 6.0);
  TestSmoothSphereCurvature();
  TestNonOrientable();
  TestErrorJumpWarning();
  TestExtrudedSolid();
  TestPointData();
  TestThreadIndependence();
  TestPartitionedGreedy(vtkTriangleCollapseDecimation::QUADRIC);
  TestPartitionedGreedy(vtkTriangleCollapseDecimation::CURVATURE);
  TestMaximumError();
  TestUnmovedPointsExact();
  TestCrowdedTargets();
  TestErrorsAndAbort();
  return meshlod::testing::Result();
}
