// vtkVertexClusterOctree: exact results on hand-made meshes, the hierarchy's properties on
// generated ones, settings and input errors.
#include "MeshLODEventCounter.h"
#include "MeshLODHierarchy.h"
#include "MeshLODHierarchyChecks.h"
#include "MeshLODTestCheck.h"
#include "MeshLODTestMeshes.h"
#include "vtkVertexClusterOctree.h"

#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIntArray.h"
#include "vtkMath.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSphereSource.h"
#include "vtkTestErrorObserver.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
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
  MESHLOD_CHECK_EQ(testing::CountRepeatedPointTriangles(h), 0);
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
  MESHLOD_CHECK_EQ(testing::CountRepeatedPointTriangles(h), 0);
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
  MESHLOD_CHECK_EQ(testing::CountRepeatedPointTriangles(h), 0);
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
  MESHLOD_CHECK_EQ(testing::CountRepeatedPointTriangles(h), 0);
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
  MESHLOD_CHECK_EQ(testing::CountRepeatedPointTriangles(filter->GetHierarchy()), 0);

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
// The same levels with one thread and with the backend in use, on an isosurface large enough
// for the passes that split their work by ranges of points or clusters (from 65,536 triangles
// in a level, and from a few hundred tree nodes for the walk that collects a cut).
void TestThreadsOnLargeInput()
{
  vtkSmartPointer<vtkPolyData> mesh = testing::MakeIsosurface(testing::Field::Gyroid, 170);
  const vtkIdType input = mesh->GetNumberOfPolys();
  std::vector<vtkSmartPointer<vtkMultiBlockDataSet>> runs;
  testing::RunWithBothBackends([&]() -> vtkSmartPointer<vtkPolyData> {
    vtkNew<vtkVertexClusterOctree> cluster;
    cluster->SetInputData(mesh);
    cluster->SetLevelModeToTargetTriangleCounts();
    cluster->AddTargetTriangleCount(input / 5);
    cluster->AddTargetTriangleCount(input / 50);
    cluster->Update();
    runs.push_back(cluster->GetHierarchy());
    return Level(cluster->GetHierarchy(), 1);
  });
  MESHLOD_CHECK_EQ(runs.size(), 2u);
  MESHLOD_CHECK_EQ(runs[0]->GetNumberOfBlocks(), 3u);
  MESHLOD_CHECK_GT(Level(runs[0], 1)->GetNumberOfPolys(), 65536);
  for (unsigned int i = 1; i < 3 && runs.size() == 2; ++i)
  {
    MESHLOD_CHECK(testing::SameMesh(Level(runs[0], i), Level(runs[1], i)));
  }
}

} // namespace

int TestVertexClusterOctree(int, char*[])
{
  TestFlatGrid();
  TestCube();
  TestHierarchy();
  TestTargetCounts();
  TestUnreachableCount();
  TestCellLimits();
  TestAllPointsCoincident();
  TestSettingsAndErrors();
  TestThreadsOnLargeInput();
  return meshlod::testing::Result();
}
