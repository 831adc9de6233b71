// A mesh whose vertex ids are shuffled is simplified on a spatially renumbered copy
// (Core/SpatialOrder.h): the check that tells scattered ids from a contouring filter's, the
// renumbering itself, and both filters on two different shuffles of one isosurface, which must
// give the same levels (the renumbered copy depends only on the geometry), with the same point
// and cell data, and the same correspondence from each one's own level 0, in its own order; and
// the topology of a shuffled mesh, whose edge neighbours are found from the sides listed by
// their lower point.
#include "vtkTriangleCollapseDecimation.h"
#include "vtkVertexClusterOctree.h"

#include "Core/SpatialOrder.h"
#include "MeshLODHierarchyChecks.h"
#include "MeshLODTestHierarchies.h"
#include "MeshLODTestCheck.h"
#include "MeshLODTestMeshes.h"

#include "vtkCellData.h"
#include "vtkCleanPolyData.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkMath.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <numeric>
#include <string>
#include <vector>

namespace
{
using namespace meshlod;
using namespace meshlod::testing;

// A shuffle of a mesh (ShuffleIds) and its map from the mesh's point ids to the shuffle's.
struct Shuffle
{
  vtkSmartPointer<vtkPolyData> Mesh;
  std::vector<vtkIdType> NewId;
};

Shuffle MakeShuffle(vtkPolyData* mesh, unsigned int seed)
{
  Shuffle s;
  s.Mesh = ShuffleIds(mesh, seed, &s.NewId);
  return s;
}

void TestScatteredCheck(vtkPolyData* isosurface, vtkPolyData* shuffled)
{
  const TriangleMesh ordered = ToTriangleMesh(isosurface);
  const TriangleMesh scattered = ToTriangleMesh(shuffled);
  // 2^13 <= 9,000-odd vertices < 2^14: shuffled ids lie about 13 bits apart, a contouring
  // filter's rows of cells far less.
  const double orderedBits = MeanCornerSpreadBits(ordered);
  const double scatteredBits = MeanCornerSpreadBits(scattered);
  MESHLOD_CHECK_LE(orderedBits, 9.0);
  MESHLOD_CHECK_GE(scatteredBits, 12.0);
  MESHLOD_CHECK(!IsOrderScattered(ordered));
  MESHLOD_CHECK(IsOrderScattered(scattered));
  // Too small to matter: never renumbered.
  vtkSmartPointer<vtkPolyData> small = MakeIcosphere(3);
  MESHLOD_CHECK(!IsOrderScattered(ToTriangleMesh(MakeShuffle(small, 3).Mesh)));
}

void TestRenumbering(const Shuffle& a, const Shuffle& b)
{
  TriangleMesh meshA = ToTriangleMesh(a.Mesh);
  TriangleMesh meshB = ToTriangleMesh(b.Mesh);
  const TriangleMesh before = meshA;
  SpatialRenumbering orderA, orderB;
  orderA.Apply(meshA);
  orderB.Apply(meshB);
  // The same mesh from either shuffle, and far from scattered.
  MESHLOD_CHECK(meshA.Points == meshB.Points);
  MESHLOD_CHECK(meshA.Triangles == meshB.Triangles);
  MESHLOD_CHECK_LE(MeanCornerSpreadBits(meshA), 9.0);
  // The maps are inverse permutations, and they carry every point and triangle over.
  const Id nv = before.GetNumberOfPoints();
  const Id nt = before.GetNumberOfTriangles();
  MESHLOD_CHECK_EQ(static_cast<Id>(orderA.OldVertex.size()), nv);
  MESHLOD_CHECK_EQ(static_cast<Id>(orderA.OldTriangle.size()), nt);
  int wrong = 0;
  for (Id v = 0; v < nv; ++v)
  {
    wrong += orderA.NewVertex[orderA.OldVertex[v]] != v;
    wrong += !std::equal(meshA.Point(v), meshA.Point(v) + 3, before.Point(orderA.OldVertex[v]));
  }
  for (Id t = 0; t < nt; ++t)
  {
    wrong += orderA.NewTriangle[orderA.OldTriangle[t]] != t;
    const Id* old = before.Triangle(orderA.OldTriangle[t]);
    for (int k = 0; k < 3; ++k)
    {
      wrong += meshA.Triangle(t)[k] != orderA.NewVertex[old[k]]; // corner order kept
    }
  }
  MESHLOD_CHECK_EQ(wrong, 0);
}

// CenterOnInput off but where `centred`: the centring samples every second input triangle (or
// fewer) in the input's order, so on another shuffle it moves the points by other samples.
vtkSmartPointer<vtkMultiBlockDataSet> Simplify(
  vtkPolyData* input, bool curvature, bool flips, bool centred = false)
{
  vtkNew<vtkTriangleCollapseDecimation> filter;
  filter->SetInputData(input);
  if (curvature)
  {
    filter->SetMethodToCurvature();
  }
  filter->SetFlipEdges(flips);
  filter->SetCenterOnInput(centred);
  filter->Update();
  // (The flips are handed back to the engine in level-0 triangle ids: some must be made.)
  if (flips)
  {
    MESHLOD_CHECK_GT(filter->GetNumberOfFlips(), 0);
  }
  return filter->GetHierarchy();
}

// The octree for 10% and 1% of the triangles (with `flips`, its levels flipped), not centred.
vtkSmartPointer<vtkMultiBlockDataSet> Cluster(vtkPolyData* input, bool flips)
{
  vtkNew<vtkVertexClusterOctree> filter;
  filter->SetInputData(input);
  filter->SetLevelModeToTargetTriangleCounts();
  filter->AddTargetTriangleCount(input->GetNumberOfPolys() / 10);
  filter->AddTargetTriangleCount(input->GetNumberOfPolys() / 100);
  filter->SetFlipEdges(flips);
  filter->SetCenterOnInput(false);
  filter->Update();
  return filter->GetHierarchy();
}

// The run on two shuffles: the same levels from level 1 on, and level 0's rows (its own input,
// in its own order) mapping each original point to the same place.
using Run = std::function<vtkSmartPointer<vtkMultiBlockDataSet>(vtkPolyData*)>;
void TestFilterOnShuffles(
  vtkPolyData* isosurface, const Shuffle& a, const Shuffle& b, const Run& run, bool flips)
{
  vtkSmartPointer<vtkMultiBlockDataSet> ha = run(a.Mesh);
  vtkSmartPointer<vtkMultiBlockDataSet> hb = run(b.Mesh);
  MESHLOD_CHECK_GE(ha->GetNumberOfBlocks(), 3u);
  MESHLOD_CHECK_EQ(ha->GetNumberOfBlocks(), hb->GetNumberOfBlocks());
  if (!flips) // (a flipped level maps onto the next level's triangles before its flips)
  {
    MESHLOD_CHECK_EQ(CountCorrespondenceViolations(ha), 0);
    MESHLOD_CHECK_EQ(CountCorrespondenceViolations(hb), 0);
  }
  MESHLOD_CHECK_EQ(CountRepeatedPointTriangles(ha), 0);
  const MeshReport input = InspectMesh(isosurface);
  // Level 0 is each one's input, as it came.
  MESHLOD_CHECK(SameMesh(Level(ha, 0), a.Mesh));
  MESHLOD_CHECK(SameMesh(Level(hb, 0), b.Mesh));
  for (unsigned int i = 1; i < std::min(ha->GetNumberOfBlocks(), hb->GetNumberOfBlocks()); ++i)
  {
    vtkPolyData* la = Level(ha, i);
    vtkPolyData* lb = Level(hb, i);
    MESHLOD_CHECK(SameMesh(la, lb));
    MESHLOD_CHECK(SameValues(
      la->GetCellData()->GetArray("CellField"), lb->GetCellData()->GetArray("CellField")));
    for (const char* name : { "Field", "MorphTarget", "MorphTargetId", "CollapseRank" })
    {
      if (i + 1 < ha->GetNumberOfBlocks() || std::string(name) == "Field")
      {
        MESHLOD_CHECK(SameValues(la->GetPointData()->GetArray(name),
          lb->GetPointData()->GetArray(name)));
      }
    }
    const MeshReport report = InspectMesh(la);
    MESHLOD_CHECK_EQ(report.NonManifoldEdges, 0);
    MESHLOD_CHECK_EQ(report.EulerCharacteristic, input.EulerCharacteristic);
  }
  // Level 0's rows, original point by original point.
  vtkPointData* pa = Level(ha, 0)->GetPointData();
  vtkPointData* pb = Level(hb, 0)->GetPointData();
  int differing = 0;
  for (const char* name : { "MorphTarget", "MorphTargetId", "CollapseRank" })
  {
    vtkDataArray* ra = pa->GetArray(name);
    vtkDataArray* rb = pb->GetArray(name);
    MESHLOD_CHECK_THEN(ra && rb, continue);
    for (vtkIdType p = 0; p < isosurface->GetNumberOfPoints(); ++p)
    {
      for (int c = 0; c < ra->GetNumberOfComponents(); ++c)
      {
        differing += ra->GetComponent(a.NewId[p], c) != rb->GetComponent(b.NewId[p], c);
      }
    }
  }
  MESHLOD_CHECK_EQ(differing, 0);
}

// With the defaults (centring on): the same triangles and interpolated data on every level; the
// points moved by centring from other samples, each by at most a quarter of its shortest edge,
// so the two places of a point lie at most half an edge apart (checked against its longest).
void TestCentredShuffles(const Shuffle& a, const Shuffle& b)
{
  vtkSmartPointer<vtkMultiBlockDataSet> ha = Simplify(a.Mesh, false, false, true);
  vtkSmartPointer<vtkMultiBlockDataSet> hb = Simplify(b.Mesh, false, false, true);
  MESHLOD_REQUIRE_EQ(ha->GetNumberOfBlocks(), hb->GetNumberOfBlocks());
  MESHLOD_CHECK_EQ(CountCorrespondenceViolations(ha), 0);
  for (unsigned int i = 1; i < ha->GetNumberOfBlocks(); ++i)
  {
    vtkPolyData* la = Level(ha, i);
    vtkPolyData* lb = Level(hb, i);
    const std::vector<TriangleIds> triangles = Triangles(la);
    MESHLOD_CHECK(triangles == Triangles(lb));
    MESHLOD_CHECK(SameValues(la->GetPointData()->GetArray("Field"),
      lb->GetPointData()->GetArray("Field")));
    MESHLOD_REQUIRE_EQ(la->GetNumberOfPoints(), lb->GetNumberOfPoints());
    std::vector<double> longest(la->GetNumberOfPoints(), 0.0);
    for (const TriangleIds& t : triangles)
    {
      for (int k = 0; k < 3; ++k)
      {
        double x[3], y[3];
        la->GetPoint(t[k], x);
        la->GetPoint(t[(k + 1) % 3], y);
        const double length = std::sqrt(vtkMath::Distance2BetweenPoints(x, y));
        longest[t[k]] = std::max(longest[t[k]], length);
        longest[t[(k + 1) % 3]] = std::max(longest[t[(k + 1) % 3]], length);
      }
    }
    int astray = 0;
    for (vtkIdType p = 0; p < la->GetNumberOfPoints(); ++p)
    {
      double x[3], y[3];
      la->GetPoint(p, x);
      lb->GetPoint(p, y);
      astray += std::sqrt(vtkMath::Distance2BetweenPoints(x, y)) > 0.5 * longest[p];
    }
    MESHLOD_CHECK_EQ(astray, 0);
  }
}

// The topology of the shuffled mesh is the isosurface's, renumbered: every edge neighbour, and
// every vertex closed and interior (the gyroid's boundary aside) as before.
void TestTopology(vtkPolyData* isosurface, const Shuffle& a)
{
  const TriangleMesh ordered = ToTriangleMesh(isosurface);
  const TriangleMesh scattered = ToTriangleMesh(a.Mesh);
  TriangleTopology before, after;
  before.Build(ordered);
  after.Build(scattered);
  MESHLOD_CHECK(before.OrientedWhenBuilt && after.OrientedWhenBuilt);
  // Triangle -> its place in the shuffle, by its corners.
  std::map<std::array<Id, 3>, Id> place;
  for (Id t = 0; t < scattered.GetNumberOfTriangles(); ++t)
  {
    const Id* tri = scattered.Triangle(t);
    place[{ tri[0], tri[1], tri[2] }] = t;
  }
  auto shuffled = [&](Id t) {
    const Id* tri = ordered.Triangle(t);
    const std::array<Id, 3> key = { static_cast<Id>(a.NewId[tri[0]]),
      static_cast<Id>(a.NewId[tri[1]]), static_cast<Id>(a.NewId[tri[2]]) };
    const auto found = place.find(key);
    return found == place.end() ? InvalidId : found->second;
  };
  int wrong = 0, boundary = 0;
  for (Id t = 0; t < ordered.GetNumberOfTriangles(); ++t)
  {
    const Id s = shuffled(t);
    MESHLOD_CHECK_THEN(s != InvalidId, return);
    for (int k = 0; k < 3; ++k)
    {
      const Id n = before.EdgeNeighbors[3 * static_cast<std::size_t>(t) + k];
      const Id m = after.EdgeNeighbors[3 * static_cast<std::size_t>(s) + k];
      wrong += n < 0 ? m != n : m != shuffled(n);
      boundary += n == BoundaryEdge;
    }
  }
  MESHLOD_CHECK_EQ(wrong, 0);
  MESHLOD_CHECK_GT(boundary, 0);
  for (Id v = 0; v < ordered.GetNumberOfPoints(); ++v)
  {
    wrong += before.VertexKinds[v] != after.VertexKinds[a.NewId[v]];
  }
  MESHLOD_CHECK_EQ(wrong, 0);
  MESHLOD_CHECK_EQ(before.CountVertices(VertexKind::NonManifold), 0);
  MESHLOD_CHECK_GT(before.CountVertices(VertexKind::Boundary), 0);
  // A triangle turned the other way is seen.
  TriangleMesh turned = scattered;
  std::swap(turned.Triangles[0], turned.Triangles[1]);
  after.Build(turned);
  MESHLOD_CHECK(!after.OrientedWhenBuilt);
}

// The renumbered runs give the same levels for any thread count.
void TestThreads(const Shuffle& a)
{
  const Run runs[] = { [](vtkPolyData* in) { return Simplify(in, false, false); },
    [](vtkPolyData* in) { return Cluster(in, false); } };
  for (const Run& run : runs)
  {
    auto levels = RunWithBothBackends([&]() {
      vtkSmartPointer<vtkMultiBlockDataSet> h = run(a.Mesh);
      auto copy = vtkSmartPointer<vtkPolyData>::New();
      copy->DeepCopy(Level(h, 1));
      return copy;
    });
    MESHLOD_CHECK(SameMesh(levels.first, levels.second));
    MESHLOD_CHECK(SameValues(levels.first->GetPointData()->GetArray("MorphTargetId"),
      levels.second->GetPointData()->GetArray("MorphTargetId")));
  }
}
} // namespace

int TestMeshLODScatteredOrder(int, char*[])
{
  // About 18,000 triangles: above the size below which ids are never renumbered; the gyroid,
  // whose levels have edges to flip (the metaballs' have none at this size).
  Field field;
  FieldFromName("gyroid", field);
  // Cleaned: coincident points (which a contouring filter makes where the surface passes through
  // a sample) would be ordered by their ids in each shuffle.
  vtkNew<vtkCleanPolyData> clean;
  clean->SetInputData(MakeIsosurface(field, ResolutionForTriangles(field, 18000)));
  clean->ConvertPolysToLinesOff(); // (triangles it collapses are dropped, not kept as lines)
  clean->ConvertLinesToPointsOff();
  clean->Update();
  vtkPolyData* isosurface = clean->GetOutput();
  // A point array to interpolate, x + 2y - z.
  vtkNew<vtkDoubleArray> values;
  values->SetName("Field");
  values->SetNumberOfTuples(isosurface->GetNumberOfPoints());
  for (vtkIdType p = 0; p < isosurface->GetNumberOfPoints(); ++p)
  {
    double x[3];
    isosurface->GetPoint(p, x);
    values->SetValue(p, x[0] + 2.0 * x[1] - x[2]);
  }
  isosurface->GetPointData()->AddArray(values);
  // A cell array, each triangle's centroid's x + 2y - z: the levels' cells take it from the
  // input triangle they descend from (level-0 triangle ids numbered back).
  vtkNew<vtkDoubleArray> cellValues;
  cellValues->SetName("CellField");
  cellValues->SetNumberOfTuples(isosurface->GetNumberOfPolys());
  vtkIdType cell = 0;
  for (const TriangleIds& t : Triangles(isosurface))
  {
    double sum = 0.0;
    for (const vtkIdType p : t)
    {
      double x[3];
      isosurface->GetPoint(p, x);
      sum += (x[0] + 2.0 * x[1] - x[2]) / 3.0;
    }
    cellValues->SetValue(cell++, sum);
  }
  isosurface->GetCellData()->AddArray(cellValues);
  const Shuffle a = MakeShuffle(isosurface, 1);
  const Shuffle b = MakeShuffle(isosurface, 2);
  TestScatteredCheck(isosurface, a.Mesh);
  TestRenumbering(a, b);
  TestTopology(isosurface, a);
  for (const bool curvature : { false, true })
  {
    for (const bool flips : { false, true })
    {
      TestFilterOnShuffles(
        isosurface, a, b, [&](vtkPolyData* in) { return Simplify(in, curvature, flips); }, flips);
    }
  }
  for (const bool flips : { false, true })
  {
    TestFilterOnShuffles(
      isosurface, a, b, [&](vtkPolyData* in) { return Cluster(in, flips); }, flips);
  }
  TestCentredShuffles(a, b);
  TestThreads(a);
  return Result();
}
