// vtkTriangleCollapseDecimation end to end: hierarchies of closed and open isosurfaces and of
// tiny meshes, checked for topology, correspondence, errors, attributes, determinism and the
// handling of bad input and settings (particular shapes: TestTriangleCollapseShapes.cxx).
#include "vtkLODGeomorph.h"
#include "vtkTriangleCollapseDecimation.h"

#include "MeshLODHierarchy.h"
#include "MeshLODHierarchyChecks.h"
#include "MeshLODSurfaceDistance.h"
#include "MeshLODTestCheck.h"
#include "MeshLODTestMeshes.h"

#include "vtkAppendPolyData.h"
#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkIntArray.h"
#include "vtkMath.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSphereSource.h"
#include "vtkSuperquadricSource.h"
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
    // Empty input: one empty level (a vtkLODGeomorph downstream then gives an empty mesh),
    // with the input's arrays, global ids included, without tuples.
    vtkNew<vtkTriangleCollapseDecimation> filter;
    vtkNew<vtkPolyData> empty;
    vtkNew<vtkIdTypeArray> pointIds, cellIds;
    pointIds->SetName("PointIds");
    cellIds->SetName("CellIds");
    empty->GetPointData()->SetGlobalIds(pointIds);
    empty->GetCellData()->SetGlobalIds(cellIds);
    filter->SetInputData(empty);
    filter->Update();
    MESHLOD_CHECK_EQ(filter->GetHierarchy()->GetNumberOfBlocks(), 1u);
    vtkPolyData* level0 = Level(filter->GetHierarchy(), 0);
    MESHLOD_CHECK_EQ(level0->GetNumberOfPoints(), 0);
    MESHLOD_CHECK(level0->GetPointData()->GetGlobalIds() != nullptr &&
      std::string(level0->GetPointData()->GetGlobalIds()->GetName()) == "PointIds");
    MESHLOD_CHECK(level0->GetCellData()->GetGlobalIds() != nullptr &&
      std::string(level0->GetCellData()->GetGlobalIds()->GetName()) == "CellIds");
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

int TestTriangleCollapseDecimation(int, char*[])
{
  TestSingleCollapse();
  TestCoincidentPoints();
  TestAllPointsCoincident();
  TestClosedIsosurface();
  TestGenus();
  TestOpenSurface();
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
