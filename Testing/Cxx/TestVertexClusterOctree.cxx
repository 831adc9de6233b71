// vtkVertexClusterOctree: exact results on hand-made meshes, the hierarchy's properties on
// generated ones, settings and input errors.
#include "MeshLODEventCounter.h"
#include "MeshLODHierarchy.h"
#include "MeshLODHierarchyChecks.h"
#include "MeshLODSurfaceDistance.h"
#include "MeshLODTestCheck.h"
#include "MeshLODTestMeshes.h"
#include "vtkVertexClusterOctree.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCellData.h"
#include "vtkCleanPolyData.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIntArray.h"
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
#include <limits>
#include <set>
#include <sstream>

namespace
{
using namespace meshlod;
using testing::Level;
using testing::Triangles;
using Triangle = testing::TriangleIds;

double Field(vtkPolyData* level, const char* name)
{
  vtkDataArray* array = level->GetFieldData()->GetArray(name);
  return array ? array->GetTuple1(0) : std::numeric_limits<double>::quiet_NaN();
}

double Distance(const double a[3], const double b[3])
{
  return std::sqrt(vtkMath::Distance2BetweenPoints(a, b));
}

// A closed cube [0, 1]^3 with n x n squares per face, outward triangles.
vtkSmartPointer<vtkPolyData> MakeCube(int n)
{
  std::vector<double> points;
  std::vector<long long> triangles;
  for (int axis = 0; axis < 3; ++axis)
  {
    for (int side = 0; side < 2; ++side)
    {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const long long base = static_cast<long long>(points.size() / 3);
      for (int j = 0; j <= n; ++j)
      {
        for (int i = 0; i <= n; ++i)
        {
          double p[3];
          p[axis] = side;
          p[u] = double(i) / n;
          p[v] = double(j) / n;
          points.insert(points.end(), p, p + 3);
        }
      }
      for (int j = 0; j < n; ++j)
      {
        for (int i = 0; i < n; ++i)
        {
          const long long a = base + j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
          if (side == 1)
          {
            triangles.insert(triangles.end(), { a, b, c, a, c, d });
          }
          else
          {
            triangles.insert(triangles.end(), { a, c, b, a, d, c });
          }
        }
      }
    }
  }
  return testing::MakePolyData(points, triangles);
}

// Triangles of every level: no repeated point, no two with the same three points.
void CheckTriangles(vtkMultiBlockDataSet* hierarchy)
{
  for (unsigned int i = 0; i < hierarchy->GetNumberOfBlocks(); ++i)
  {
    std::set<Triangle> seen;
    vtkIdType degenerate = 0, duplicate = 0;
    for (Triangle t : Triangles(Level(hierarchy, i)))
    {
      degenerate += (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) ? 1 : 0;
      std::sort(t.begin(), t.end());
      duplicate += seen.insert(t).second ? 0 : 1;
    }
    MESHLOD_CHECK_EQ(degenerate, 0);
    MESHLOD_CHECK_EQ(duplicate, 0);
  }
}

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
// A flat square grid: four quadrants, each holding one corner, cluster to the corners exactly.
void TestFlatGrid()
{
  vtkNew<vtkVertexClusterOctree> filter;
  filter->SetInputData(testing::MakeGrid(8, 8));
  filter->SetLevelModeToEpsilonList();
  filter->AddEpsilonValue(0.05); // 0.57 world units: too small to merge two corners
  filter->MeasureLevelErrorsOn();
  filter->Update();
  vtkMultiBlockDataSet* h = filter->GetHierarchy();
  MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 2u);
  MESHLOD_CHECK(CheckHierarchyLayout(h, true).empty());
  vtkPolyData* level = Level(h, 1);
  MESHLOD_CHECK_EQ(level->GetNumberOfPolys(), 2);
  MESHLOD_CHECK_EQ(level->GetNumberOfPoints(), 4);
  const double corners[4][3] = { { 0, 0, 0 }, { 8, 0, 0 }, { 0, 8, 0 }, { 8, 8, 0 } };
  for (const auto& corner : corners)
  {
    double nearest = VTK_DOUBLE_MAX;
    for (vtkIdType p = 0; p < level->GetNumberOfPoints(); ++p)
    {
      nearest = std::min(nearest, Distance(corner, level->GetPoint(p)));
    }
    MESHLOD_CHECK_LE(nearest, 1e-9);
  }
  MESHLOD_CHECK_LE(Field(level, names::EstimatedError), 1e-6);
  MESHLOD_CHECK_LE(Field(level, names::MeasuredHausdorff), 1e-6);
  // Both triangles face +z like the input.
  for (const Triangle& t : Triangles(level))
  {
    double a[3], b[3], c[3], n[3];
    level->GetPoint(t[0], a);
    level->GetPoint(t[1], b);
    level->GetPoint(t[2], c);
    const double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    const double v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
    vtkMath::Cross(u, v, n);
    MESHLOD_CHECK_GT(n[2], 0.0);
  }
}

//------------------------------------------------------------------------------
// A cube: the clusters of its eight octants collapse onto the corners with zero error, so the
// cube is kept exactly with 12 triangles.
void TestCube()
{
  vtkNew<vtkVertexClusterOctree> filter;
  filter->SetInputData(MakeCube(6));
  filter->SetLevelModeToEpsilonList();
  filter->AddEpsilonValue(1e-6);
  filter->Update();
  vtkMultiBlockDataSet* h = filter->GetHierarchy();
  MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 2u);
  vtkPolyData* level = Level(h, 1);
  MESHLOD_CHECK_EQ(level->GetNumberOfPolys(), 12);
  MESHLOD_CHECK_EQ(level->GetNumberOfPoints(), 8);
  for (vtkIdType p = 0; p < level->GetNumberOfPoints(); ++p)
  {
    const double* x = level->GetPoint(p);
    for (int c = 0; c < 3; ++c)
    {
      MESHLOD_CHECK_LE(std::min(std::abs(x[c]), std::abs(x[c] - 1.0)), 1e-6);
    }
  }
  MESHLOD_CHECK_LE(Field(level, names::EstimatedError), 1e-6);
  // Closed and consistently oriented: every directed edge once, its reverse once.
  std::map<std::pair<vtkIdType, vtkIdType>, int> directed;
  for (const Triangle& t : Triangles(level))
  {
    for (int k = 0; k < 3; ++k)
    {
      ++directed[{ t[k], t[(k + 1) % 3] }];
    }
  }
  for (const auto& edge : directed)
  {
    MESHLOD_CHECK_EQ(edge.second, 1);
    MESHLOD_CHECK_EQ(directed.count({ edge.first.second, edge.first.first }), 1u);
  }
  CheckTriangles(h);
}

//------------------------------------------------------------------------------
// The hierarchy of a generated surface: nesting through MorphTargetId, consistent triangles,
// ranks, point and cell data on every level, errors within epsilon.
vtkSmartPointer<vtkPolyData> DecoratedMetaballs()
{
  vtkSmartPointer<vtkPolyData> mesh = testing::MakeIsosurface(testing::Field::Metaballs, 40);
  vtkNew<vtkFloatArray> height;
  height->SetName("Height");
  vtkNew<vtkIntArray> label;
  label->SetName("Label");
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    height->InsertNextValue(static_cast<float>(mesh->GetPoint(p)[2]));
    label->InsertNextValue(static_cast<int>(p % 7));
  }
  mesh->GetPointData()->AddArray(height);
  mesh->GetPointData()->AddArray(label);
  // A constant far from 0 (a date, a map coordinate): averaged, it must stay exact.
  vtkNew<vtkDoubleArray> constant;
  constant->SetName("Constant");
  constant->SetNumberOfTuples(mesh->GetNumberOfPoints());
  constant->Fill(1e9 + 0.25);
  mesh->GetPointData()->AddArray(constant);
  vtkNew<vtkIntArray> triangleId;
  triangleId->SetName("TriangleId");
  for (vtkIdType c = 0; c < mesh->GetNumberOfPolys(); ++c)
  {
    triangleId->InsertNextValue(static_cast<int>(c));
  }
  mesh->GetCellData()->AddArray(triangleId);
  return mesh;
}

void TestHierarchy()
{
  vtkSmartPointer<vtkPolyData> mesh = DecoratedMetaballs();
  vtkNew<vtkIntArray> run; // field data: passed to every level
  run->SetName("RunNumber");
  run->InsertNextValue(42);
  mesh->GetFieldData()->AddArray(run);
  // ... but for the levels' own names, even where a level lacks the array (not measured).
  vtkNew<vtkDoubleArray> rms;
  rms->SetName(names::MeasuredRMS);
  rms->InsertNextValue(0.125);
  mesh->GetFieldData()->AddArray(rms);
  vtkNew<vtkVertexClusterOctree> filter;
  filter->SetInputData(mesh);
  filter->SetNumberOfLevels(4);
  filter->SetEpsilon(0.0005);
  filter->SetEpsilonFactor(3.0);
  filter->MeasureLevelErrorsOn();
  filter->Update();
  vtkMultiBlockDataSet* h = filter->GetHierarchy();
  MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 5u);
  MESHLOD_CHECK(CheckHierarchyLayout(h, true).empty());
  for (unsigned int i = 0; i < h->GetNumberOfBlocks(); ++i)
  {
    MESHLOD_CHECK(Level(h, i)->GetFieldData()->GetArray("RunNumber") != nullptr);
    // Measured here: the level's own value, 0 at level 0.
    MESHLOD_CHECK(i > 0 || Field(Level(h, i), names::MeasuredRMS) == 0.0);
  }
  {
    vtkNew<vtkVertexClusterOctree> unmeasured;
    unmeasured->SetInputData(mesh);
    unmeasured->SetNumberOfLevels(1);
    unmeasured->Update();
    for (unsigned int i = 0; i < unmeasured->GetHierarchy()->GetNumberOfBlocks(); ++i)
    {
      MESHLOD_CHECK(
        Level(unmeasured->GetHierarchy(), i)->GetFieldData()->GetArray(names::MeasuredRMS) ==
        nullptr);
    }
  }
  CheckTriangles(h);
  const unsigned int levels = h->GetNumberOfBlocks();
  const double diagonal = mesh->GetLength();

  // Chained maps from input points to every level.
  std::vector<std::vector<vtkIdType>> chain(levels);
  chain[0].resize(Level(h, 0)->GetNumberOfPoints());
  for (vtkIdType p = 0; p < static_cast<vtkIdType>(chain[0].size()); ++p)
  {
    chain[0][p] = p;
  }
  for (unsigned int i = 0; i + 1 < levels; ++i)
  {
    vtkPolyData* level = Level(h, i);
    vtkPolyData* next = Level(h, i + 1);
    MESHLOD_CHECK_LT(next->GetNumberOfPolys(), level->GetNumberOfPolys());
    vtkDataArray* targetId = level->GetPointData()->GetArray(names::MorphTargetId);
    vtkDataArray* target = level->GetPointData()->GetArray(names::MorphTarget);
    vtkDataArray* rank = level->GetPointData()->GetArray(names::CollapseRank);
    std::vector<int> preimages(next->GetNumberOfPoints(), 0);
    std::map<vtkIdType, vtkIdType> rankOfTarget;
    vtkIdType rankMismatch = 0, badTargets = 0, unmovedButChanged = 0;
    for (vtkIdType p = 0; p < level->GetNumberOfPoints(); ++p)
    {
      const vtkIdType to = static_cast<vtkIdType>(targetId->GetTuple1(p));
      ++preimages[to];
      double x[3];
      target->GetTuple(p, x);
      badTargets += Distance(x, next->GetPoint(to)) > 1e-6 * diagonal ? 1 : 0;
      const vtkIdType r = static_cast<vtkIdType>(rank->GetTuple1(p));
      auto inserted = rankOfTarget.emplace(to, r);
      rankMismatch += inserted.first->second != r ? 1 : 0;
      unmovedButChanged +=
        (r == -1 && Distance(level->GetPoint(p), next->GetPoint(to)) > 1e-6 * diagonal) ? 1 : 0;
    }
    MESHLOD_CHECK_EQ(badTargets, 0);
    MESHLOD_CHECK_EQ(rankMismatch, 0);
    MESHLOD_CHECK_EQ(unmovedButChanged, 0);
    MESHLOD_CHECK_EQ(std::count(preimages.begin(), preimages.end(), 0), 0);
    chain[i + 1].resize(chain[0].size());
    for (size_t p = 0; p < chain[0].size(); ++p)
    {
      chain[i + 1][p] = static_cast<vtkIdType>(targetId->GetTuple1(chain[i][p]));
    }
  }

  // Every triangle of every level is its input triangle with the corners mapped through the
  // chain (same order): the levels are one nested clustering of the input.
  const std::vector<Triangle> input = Triangles(Level(h, 0));
  for (unsigned int i = 1; i < levels; ++i)
  {
    vtkPolyData* level = Level(h, i);
    vtkDataArray* triangleId = level->GetCellData()->GetArray("TriangleId");
    MESHLOD_CHECK(triangleId != nullptr);
    if (!triangleId)
    {
      continue;
    }
    vtkIdType mismatch = 0;
    const std::vector<Triangle> tris = Triangles(level);
    for (size_t t = 0; t < tris.size(); ++t)
    {
      const Triangle& source = input[static_cast<size_t>(triangleId->GetTuple1(t))];
      const Triangle mapped = { chain[i][source[0]], chain[i][source[1]], chain[i][source[2]] };
      mismatch += mapped == tris[t] ? 0 : 1;
    }
    MESHLOD_CHECK_EQ(mismatch, 0);
  }

  // Point data on every level; errors within the level's epsilon.
  double range[2];
  mesh->GetPointData()->GetArray("Height")->GetRange(range);
  for (unsigned int i = 1; i < levels; ++i)
  {
    vtkPolyData* level = Level(h, i);
    vtkDataArray* height = level->GetPointData()->GetArray("Height");
    vtkDataArray* label = level->GetPointData()->GetArray("Label");
    MESHLOD_CHECK(height && label && label->GetDataType() == VTK_INT);
    if (height && label)
    {
      double levelRange[2], labelRange[2];
      height->GetRange(levelRange);
      label->GetRange(labelRange);
      MESHLOD_CHECK_GE(levelRange[0], range[0] - 1e-6);
      MESHLOD_CHECK_LE(levelRange[1], range[1] + 1e-6);
      MESHLOD_CHECK_GE(labelRange[0], 0.0);
      MESHLOD_CHECK_LE(labelRange[1], 6.0);
    }
    vtkDataArray* constant = level->GetPointData()->GetArray("Constant");
    MESHLOD_CHECK(constant != nullptr);
    if (constant)
    {
      double constantRange[2];
      constant->GetRange(constantRange);
      MESHLOD_CHECK_EQ(constantRange[0], 1e9 + 0.25);
      MESHLOD_CHECK_EQ(constantRange[1], 1e9 + 0.25);
    }
    const double epsilon = filter->GetLevelEpsilon(static_cast<int>(i));
    MESHLOD_CHECK_GT(epsilon, 0.0);
    MESHLOD_CHECK_LE(Field(level, names::EstimatedError), epsilon * (1 + 1e-6));
    // Clusters bound the root mean squared distance to their planes; the surface stays within a
    // few epsilon of the input.
    MESHLOD_CHECK_LE(Field(level, names::MeasuredHausdorff), 4.0 * epsilon);
    MESHLOD_CHECK_LE(Field(level, names::MeasuredRMS), epsilon);
  }
}

//------------------------------------------------------------------------------
// Target triangle counts are met within 0.2% (the search stops there).
void TestTargetCounts()
{
  vtkSmartPointer<vtkPolyData> mesh = testing::MakeIsosurface(testing::Field::Torus, 60);
  const vtkIdType n = mesh->GetNumberOfPolys();
  vtkNew<vtkVertexClusterOctree> filter;
  filter->SetInputData(mesh);
  filter->SetLevelModeToTargetTriangleCounts();
  const vtkIdType targets[3] = { n / 4, n / 20, n / 100 };
  for (const vtkIdType target : targets)
  {
    filter->AddTargetTriangleCount(target);
  }
  filter->Update();
  vtkMultiBlockDataSet* h = filter->GetHierarchy();
  MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 4u);
  MESHLOD_CHECK(CheckHierarchyLayout(h, true).empty());
  for (unsigned int i = 1; i < h->GetNumberOfBlocks(); ++i)
  {
    const vtkIdType count = Level(h, i)->GetNumberOfPolys();
    const vtkIdType target = targets[i - 1];
    MESHLOD_CHECK_LE(std::abs(count - target), std::max<vtkIdType>(2, target / 500));
    MESHLOD_CHECK_EQ(static_cast<vtkIdType>(Field(Level(h, i), names::NumberOfTriangles)), count);
  }
  CheckTriangles(h);
}

//------------------------------------------------------------------------------
// Counts on a flat grid, where every cluster has zero error: met within their tolerance at zero
// error, the smallest cells merging first (before zero-error nodes were ordered by cell size,
// every epsilon collapsed the grid to 8 triangles and 200 was out of reach); counts the grid
// cannot give are reported.
void TestUnreachableCount()
{
  vtkNew<vtkTest::ErrorObserver> observer;
  vtkNew<vtkVertexClusterOctree> filter;
  filter->AddObserver(vtkCommand::WarningEvent, observer);
  filter->SetInputData(testing::MakeGrid(32, 32));
  filter->SetLevelModeToTargetTriangleCounts();
  const std::vector<vtkIdType> targets = { 1000, 200, 50 };
  for (const vtkIdType asked : targets)
  {
    filter->AddTargetTriangleCount(asked);
  }
  filter->Update();
  vtkMultiBlockDataSet* h = filter->GetHierarchy();
  MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 1u + targets.size());
  MESHLOD_CHECK(!observer->GetWarning());
  for (unsigned int i = 1; i < h->GetNumberOfBlocks() && i <= targets.size(); ++i)
  {
    vtkPolyData* level = Level(h, i);
    MESHLOD_CHECK_LE(std::abs(level->GetNumberOfPolys() - targets[i - 1]), 2);
    MESHLOD_CHECK_LE(Field(level, names::EstimatedError), 1e-9); // rounding of a 32-unit grid
    double bounds[6];
    level->GetBounds(bounds);
    MESHLOD_CHECK_EQ(bounds[4], 0.0);
    MESHLOD_CHECK_EQ(bounds[5], 0.0);
  }
  CheckTriangles(h);
  MESHLOD_CHECK_EQ(testing::CountCorrespondenceViolations(h), 0);

  // More than the input has: the level is the input's count, and the warning says why.
  observer->Clear();
  filter->RemoveAllTargetTriangleCounts();
  filter->AddTargetTriangleCount(5000);
  filter->AddTargetTriangleCount(2);
  filter->Update();
  MESHLOD_CHECK_EQ(Level(filter->GetHierarchy(), 1)->GetNumberOfPolys(), 2 * 32 * 32);
  MESHLOD_CHECK(observer->GetWarningMessage().find("at least the 2048 of level 0") !=
    std::string::npos);
  MESHLOD_CHECK_LE(Level(filter->GetHierarchy(), 2)->GetNumberOfPolys(), 4); // then merges again
  // So do counts beyond the core's 32-bit ids (they once wrapped to 0 or below and gave 8
  // triangles).
  for (const long long asked : { 1LL << 31, 1LL << 32, 1000000000000LL })
  {
    if (asked > static_cast<long long>(VTK_ID_MAX))
    {
      continue; // a build with 32-bit vtkIdType cannot ask for it
    }
    filter->RemoveAllTargetTriangleCounts();
    filter->AddTargetTriangleCount(static_cast<vtkIdType>(asked));
    filter->Update();
    MESHLOD_CHECK_EQ(Level(filter->GetHierarchy(), 1)->GetNumberOfPolys(), 2 * 32 * 32);
  }

  // Small counts met within their tolerance (2 triangles) by the cut of the level before (5, 3,
  // 3, 2, 2 triangles for 5 to 1): every level is kept, and each repeated one is said.
  observer->Clear();
  filter->RemoveAllTargetTriangleCounts();
  for (const vtkIdType asked : { 5, 4, 3, 2, 1 })
  {
    filter->AddTargetTriangleCount(asked);
  }
  filter->Update();
  h = filter->GetHierarchy();
  MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 6u);
  int repeats = 0;
  for (unsigned int i = 2; i < h->GetNumberOfBlocks(); ++i)
  {
    const vtkIdType count = Level(h, i)->GetNumberOfPolys();
    MESHLOD_CHECK_LE(count, Level(h, i - 1)->GetNumberOfPolys());
    const std::string said = "Level " + std::to_string(i) + ": asked for " +
      std::to_string(6 - i) + " triangles, reached " + std::to_string(count) +
      ", the count of level " + std::to_string(i - 1);
    const bool repeated = count == Level(h, i - 1)->GetNumberOfPolys();
    repeats += repeated ? 1 : 0;
    MESHLOD_CHECK_EQ(observer->GetWarningMessage().find(said) != std::string::npos, repeated);
  }
  MESHLOD_CHECK_GT(repeats, 0);

  // In the epsilon modes the size order does not apply: epsilon 0 merges every cluster of zero
  // error, a lossless reduction of the flat grid to the few triangles its corners need.
  {
    vtkNew<vtkVertexClusterOctree> lossless;
    lossless->SetInputData(testing::MakeGrid(32, 32));
    lossless->SetLevelModeToEpsilonList();
    lossless->AddEpsilonValue(0.0);
    lossless->Update();
    MESHLOD_CHECK_EQ(lossless->GetHierarchy()->GetNumberOfBlocks(), 2u);
    MESHLOD_CHECK_LE(Level(lossless->GetHierarchy(), 1)->GetNumberOfPolys(), 8);
  }

  // MaximumCellSize keeps more: asked for 8 triangles (what the grid gives without it), cells
  // of at most 4.5 units leave at least 8 x 8 clusters.
  filter->RemoveAllTargetTriangleCounts();
  filter->AddTargetTriangleCount(8);
  observer->Clear();
  filter->SetMaximumCellSize(0.1); // of the diagonal (45 units): cells of at most 4.5 units
  filter->Update();
  const vtkIdType kept = Level(filter->GetHierarchy(), 1)->GetNumberOfPolys();
  std::cerr << "  flat 32 x 32 grid, MaximumCellSize 0.1: " << kept << " triangles\n";
  MESHLOD_CHECK_GE(kept, 2 * 7 * 7);
  MESHLOD_CHECK(observer->GetWarning());
  CheckTriangles(filter->GetHierarchy());

  // A very noisy small sphere, asked for far fewer triangles than its folds allow: every trial
  // of the search either keeps too many or merges it whole. The level is the fewest triangles
  // found, with the warning (asked for 200: 1,654 triangles; asked for 50, there was no level).
  vtkNew<vtkSphereSource> source;
  source->SetThetaResolution(30);
  source->SetPhiResolution(30);
  source->Update();
  vtkNew<vtkPolyData> rough;
  rough->DeepCopy(source->GetOutput());
  rough->GetPointData()->Initialize();
  testing::PerturbRadially(rough, 1.5, 1); // radii from 0.25 to 1.75
  for (const vtkIdType asked : { 50, 1 })
  {
    observer->Clear();
    filter->SetInputData(rough);
    filter->SetMaximumCellSize(0.0); // the default: no limit
    filter->RemoveAllTargetTriangleCounts();
    filter->AddTargetTriangleCount(asked);
    filter->Update();
    MESHLOD_CHECK_EQ(filter->GetHierarchy()->GetNumberOfBlocks(), 2u);
    if (filter->GetHierarchy()->GetNumberOfBlocks() == 2)
    {
      const vtkIdType got = Level(filter->GetHierarchy(), 1)->GetNumberOfPolys();
      std::cerr << "  very noisy sphere asked for " << asked << ": " << got << " triangles\n";
      MESHLOD_CHECK_GT(got, 0);
      MESHLOD_CHECK_LT(got, rough->GetNumberOfPolys());
      MESHLOD_CHECK(observer->GetWarningMessage().find(
                      "asked for " + std::to_string(asked) + " triangles, reached") !=
        std::string::npos);
    }
  }
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
  MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 3u);
  if (h->GetNumberOfBlocks() != 3)
  {
    return;
  }
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
  CheckTriangles(h);
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
  MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 3u);
  if (h->GetNumberOfBlocks() != 3)
  {
    return;
  }
  vtkPolyData* coarse = Level(h, 2);
  const SurfaceDistance d = MeasureSurfaceDistance(mesh, coarse);
  std::cerr << "  subdivided icosahedron asked for 205: " << coarse->GetNumberOfPolys()
            << " triangles, Hausdorff " << d.HausdorffPercent() << "%\n";
  MESHLOD_CHECK_LT(coarse->GetNumberOfPolys(), Level(h, 1)->GetNumberOfPolys());
  MESHLOD_CHECK_LE(d.HausdorffPercent(), 1e-4); // rounding of the float points only
  MESHLOD_CHECK(observer->GetWarningMessage().find("asked for 205 triangles") !=
    std::string::npos);
  CheckTriangles(h);
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
  MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 3u);
  if (h->GetNumberOfBlocks() != 3)
  {
    return;
  }
  CheckTriangles(h);
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
  std::vector<double> points;
  std::vector<long long> triangles;
  for (int copy = 0; copy < 2; ++copy)
  {
    for (vtkIdType p = 0; p < n; ++p)
    {
      double x[3];
      sphere->GetPoint(p, x);
      points.insert(points.end(), { copy == 0 ? x[0] : 2.0 * p0[0] - x[0], x[1], x[2] });
    }
  }
  for (const Triangle& t : Triangles(sphere))
  {
    triangles.insert(triangles.end(), { t[0], t[1], t[2] });
    // The mirror image reverses the orientation; B's copy of m is A's m.
    auto b = [&](vtkIdType v) { return static_cast<long long>(v == m ? m : v + n); };
    triangles.insert(triangles.end(), { b(t[0]), b(t[2]), b(t[1]) });
  }
  vtkSmartPointer<vtkPolyData> twin = testing::MakePolyData(points, triangles);

  vtkNew<vtkVertexClusterOctree> filter;
  filter->SetInputData(twin);
  filter->SetNumberOfLevels(3);
  filter->SetEpsilon(0.01);
  filter->Update();
  vtkMultiBlockDataSet* h = filter->GetHierarchy();
  MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 4u);
  CheckTriangles(h);
  for (unsigned int i = 1; i < h->GetNumberOfBlocks(); ++i)
  {
    vtkPolyData* level = Level(h, i);
    MESHLOD_CHECK_LT(level->GetNumberOfPolys(), twin->GetNumberOfPolys());
    vtkIdType at = -1;
    for (vtkIdType p = 0; p < level->GetNumberOfPoints(); ++p)
    {
      at = Distance(level->GetPoint(p), p0) == 0.0 ? p : at;
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
  MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 3u);
  if (h->GetNumberOfBlocks() != 3)
  {
    return;
  }
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
  CheckTriangles(h);
}

void TestSettingsAndErrors()
{
  vtkNew<vtkTest::ErrorObserver> observer;
  vtkNew<vtkVertexClusterOctree> filter;
  filter->AddObserver(vtkCommand::ErrorEvent, observer);
  filter->AddObserver(vtkCommand::WarningEvent, observer);
  filter->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, observer);

  // Empty input: one empty level, no message.
  vtkNew<vtkPolyData> empty;
  filter->SetInputData(empty);
  filter->Update();
  MESHLOD_CHECK(!observer->GetError());
  MESHLOD_CHECK(!observer->GetWarning());
  MESHLOD_CHECK_EQ(filter->GetHierarchy()->GetNumberOfBlocks(), 1u);
  MESHLOD_CHECK_EQ(Level(filter->GetHierarchy(), 0)->GetNumberOfPoints(), 0);
  // With baking, the texture output has its block for that level too.
  filter->BakeTextureOn();
  filter->Update();
  MESHLOD_CHECK(!observer->GetError());
  MESHLOD_CHECK_EQ(filter->GetTextures()->GetNumberOfBlocks(), 1u);
  filter->BakeTextureOff();

  // NaN settings: an error naming the setting, no output (vtkSetClampMacro lets NaN through;
  // an epsilon of NaN crashed while assigning clusters).
  filter->SetInputData(testing::MakeGrid(4, 4));
  filter->SetEpsilon(std::numeric_limits<double>::quiet_NaN());
  filter->Update();
  MESHLOD_CHECK(observer->GetErrorMessage().find("Epsilon is NaN") != std::string::npos);
  MESHLOD_CHECK_EQ(filter->GetHierarchy()->GetNumberOfBlocks(), 0u);
  observer->Clear();
  filter->SetEpsilon(0.0);

  // NaN point: an error, no output.
  vtkSmartPointer<vtkPolyData> bad = testing::MakeGrid(2, 2);
  bad->GetPoints()->SetPoint(4, std::numeric_limits<double>::quiet_NaN(), 0, 0);
  filter->SetInputData(bad);
  filter->Update();
  MESHLOD_CHECK(observer->GetError());
  MESHLOD_CHECK_EQ(filter->GetHierarchy()->GetNumberOfBlocks(), 0u);
  observer->Clear();
  // A NaN point that no triangle uses is dropped like any unused point: every level is the
  // same as without it.
  const auto runOctree = [&](vtkPolyData* input) {
    vtkNew<vtkVertexClusterOctree> octree;
    octree->AddObserver(vtkCommand::ErrorEvent, observer);
    octree->SetInputData(input);
    octree->Update();
    MESHLOD_CHECK_GT(octree->GetHierarchy()->GetNumberOfBlocks(), 2u);
    return vtkSmartPointer<vtkMultiBlockDataSet>(octree->GetHierarchy());
  };
  MESHLOD_CHECK_EQ(testing::CountLevelsChangedByUnusedNaNPoint(runOctree), 0);
  MESHLOD_CHECK(!observer->GetError());

  // An error whose message holds `text`, then the observer cleared.
  auto expectError = [&](const char* text)
  {
    filter->Update();
    MESHLOD_CHECK(observer->GetError());
    MESHLOD_CHECK(observer->GetErrorMessage().find(text) != std::string::npos);
    observer->Clear();
  };

  // Coordinates beyond what single-precision cluster errors hold: an error (every level was
  // the input again at 1e45).
  for (const double scale : { 1e35, 1e-35 })
  {
    vtkSmartPointer<vtkPolyData> huge = testing::MakeGrid(4, 4);
    testing::Scale(huge, scale);
    filter->SetInputData(huge);
    expectError("bounding-box diagonal");
    MESHLOD_CHECK_EQ(filter->GetHierarchy()->GetNumberOfBlocks(), 0u);
  }

  // Bad level lists.
  filter->SetInputData(testing::MakeGrid(4, 4));
  filter->SetLevelModeToEpsilonList();
  expectError("AddEpsilonValue");
  filter->AddEpsilonValue(0.2);
  filter->AddEpsilonValue(0.1);
  expectError("increasing");
  filter->RemoveAllEpsilonValues(); // the same value twice would make the same level twice
  filter->AddEpsilonValue(0.1);
  filter->AddEpsilonValue(0.1);
  expectError("strictly increasing");
  filter->SetLevelModeToTargetTriangleCounts();
  filter->AddTargetTriangleCount(5);
  filter->AddTargetTriangleCount(10);
  expectError("decreasing");
  filter->RemoveAllTargetTriangleCounts();
  filter->AddTargetTriangleCount(5);
  filter->AddTargetTriangleCount(5);
  expectError("strictly decreasing");
  // Clearing a list that is already empty changes nothing (no re-execution).
  filter->RemoveAllTargetTriangleCounts();
  filter->RemoveAllEpsilonValues();
  const vtkMTimeType cleared = filter->GetMTime();
  filter->RemoveAllTargetTriangleCounts();
  filter->RemoveAllEpsilonValues();
  MESHLOD_CHECK_EQ(filter->GetMTime(), cleared);

  // Baking with nothing to bake.
  filter->SetLevelModeToGeometricEpsilon();
  filter->BakeTextureOn();
  filter->Update();
  MESHLOD_CHECK(observer->GetError());
  MESHLOD_CHECK(observer->GetErrorMessage().find("BakeTexture") != std::string::npos);
  observer->Clear();
  filter->BakeTextureOff();

  // Clamped settings.
  filter->SetNumberOfLevels(100);
  MESHLOD_CHECK_EQ(filter->GetNumberOfLevels(), 32);
  filter->SetEpsilonFactor(0.5);
  MESHLOD_CHECK_EQ(filter->GetEpsilonFactor(), 1.0);
  filter->SetTextureResolution(3);
  MESHLOD_CHECK_EQ(filter->GetTextureResolution(), 16);

  // Progress events, and PrintSelf names every setting.
  const testing::EventCounter progressEvents(filter, vtkCommand::ProgressEvent);
  filter->SetNumberOfLevels(2);
  filter->SetEpsilon(0.01);
  filter->SetInputData(testing::MakeIcosphere(3));
  filter->Update();
  MESHLOD_CHECK(!observer->GetError());
  MESHLOD_CHECK_GE(progressEvents.Count, 3);
  std::ostringstream printed;
  filter->Print(printed);
  for (const char* setting : { "LevelMode",
         "NumberOfLevels",
         "Epsilon:",
         "EpsilonFactor",
         "EpsilonValues",
         "TargetTriangleCounts",
         "RelativeUnits",
         "MaximumCellSize",
         "MaximumPointsPerCell",
         "RepresentativeIterations",
         "BoundaryWeight",
         "ComputeNormals",
         "MeasureLevelErrors",
         "BakeTexture",
         "TextureResolution",
         "ColorArrayName" })
  {
    MESHLOD_CHECK(printed.str().find(setting) != std::string::npos);
  }
}

//------------------------------------------------------------------------------
// MaximumPointsPerCell and MaximumCellSize bound the clusters (§2.4 cases a and b).
void TestCellLimits()
{
  vtkSmartPointer<vtkPolyData> grid = testing::MakeGrid(32, 32);
  for (const bool bySize : { false, true })
  {
    vtkNew<vtkVertexClusterOctree> filter;
    filter->SetInputData(grid);
    filter->SetLevelModeToEpsilonList();
    filter->AddEpsilonValue(1.0); // everything flat would merge
    if (bySize)
    {
      filter->RelativeUnitsOff();
      filter->SetMaximumCellSize(8.5); // cells of at most 8 units: 4 x 4 of them
    }
    else
    {
      filter->SetMaximumPointsPerCell(30);
    }
    filter->Update();
    vtkPolyData* level0 = Level(filter->GetHierarchy(), 0);
    vtkPolyData* level1 = Level(filter->GetHierarchy(), 1);
    vtkDataArray* targetId = level0->GetPointData()->GetArray(names::MorphTargetId);
    std::vector<int> members(level1->GetNumberOfPoints(), 0);
    std::vector<std::array<double, 4>> box(level1->GetNumberOfPoints(),
      { VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX });
    for (vtkIdType p = 0; p < level0->GetNumberOfPoints(); ++p)
    {
      const vtkIdType to = static_cast<vtkIdType>(targetId->GetTuple1(p));
      ++members[to];
      const double* x = level0->GetPoint(p);
      box[to] = { std::min(box[to][0], x[0]),
        std::max(box[to][1], x[0]),
        std::min(box[to][2], x[1]),
        std::max(box[to][3], x[1]) };
    }
    for (vtkIdType q = 0; q < level1->GetNumberOfPoints(); ++q)
    {
      if (bySize)
      {
        MESHLOD_CHECK_LE(box[q][1] - box[q][0], 8.0);
        MESHLOD_CHECK_LE(box[q][3] - box[q][2], 8.0);
      }
      else
      {
        MESHLOD_CHECK_LE(members[q], 30);
      }
    }
    MESHLOD_CHECK_LT(level1->GetNumberOfPolys(), grid->GetNumberOfPolys() / 4);
  }
}

// All points at one place (a bounding-box diagonal of 0, which is no error): every cluster
// merges at any epsilon, so the hierarchy is level 0 alone, with a warning saying why.
void TestAllPointsCoincident()
{
  vtkSmartPointer<vtkPolyData> sphere = testing::MakeIcosphere(3);
  for (vtkIdType p = 0; p < sphere->GetNumberOfPoints(); ++p)
  {
    sphere->GetPoints()->SetPoint(p, 1.0, 2.0, 3.0);
  }
  vtkNew<vtkTest::ErrorObserver> observer;
  vtkNew<vtkVertexClusterOctree> filter;
  filter->AddObserver(vtkCommand::ErrorEvent, observer);
  filter->AddObserver(vtkCommand::WarningEvent, observer);
  filter->SetInputData(sphere);
  filter->Update();
  MESHLOD_CHECK(!observer->GetError());
  MESHLOD_CHECK_EQ(filter->GetHierarchy()->GetNumberOfBlocks(), 1u);
  MESHLOD_CHECK_EQ(
    Level(filter->GetHierarchy(), 0)->GetNumberOfPolys(), sphere->GetNumberOfPolys());
  MESHLOD_CHECK(observer->GetWarningMessage().find("Level 1 would keep no triangle") !=
    std::string::npos);
}
} // namespace

int TestVertexClusterOctree(int, char*[])
{
  TestFlatGrid();
  TestCube();
  TestHierarchy();
  TestTargetCounts();
  TestUnreachableCount();
  TestFlatFacedSolid();
  TestFlipFreeRepresentatives();
  TestSheetsAlongCurve();
  TestBoundaries();
  TestNonManifold();
  TestRoughPlane();
  TestNoisyTerrain();
  TestNoisyTerrainCounts();
  TestNoisySphereCounts();
  TestThinTube();
  TestHighValenceFan();
  TestCellLimits();
  TestAllPointsCoincident();
  TestSettingsAndErrors();
  return meshlod::testing::Result();
}
