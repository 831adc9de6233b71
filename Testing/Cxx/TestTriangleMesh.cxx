// Core topology on tiny hand-made meshes with exact expected results.
#include "Core/FreshMemory.h"
#include "Core/TriangleMesh.h"
#include "MeshLODInputMesh.h"
#include "MeshLODTestCheck.h"
#include "MeshLODTestMeshes.h"

#include "vtkCellArray.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <limits>
#include <cstdint>
#include <numeric>
#include <vector>

namespace
{
using namespace meshlod;

// Core mesh straight from a polydata of triangles (no validation).
TriangleMesh ToCore(vtkPolyData* poly)
{
  TriangleMesh mesh;
  for (vtkIdType i = 0; i < poly->GetNumberOfPoints(); ++i)
  {
    double p[3];
    poly->GetPoint(i, p);
    mesh.Points.insert(mesh.Points.end(), p, p + 3);
  }
  vtkIdType n;
  const vtkIdType* ids;
  for (vtkIdType c = 0; c < poly->GetNumberOfPolys(); ++c)
  {
    poly->GetPolys()->GetCellAtId(c, n, ids);
    for (vtkIdType k = 0; k < n; ++k)
    {
      mesh.Triangles.push_back(static_cast<Id>(ids[k]));
    }
  }
  return mesh;
}

void TestOctahedron()
{
  TriangleMesh mesh = ToCore(testing::MakeOctahedron());
  TriangleTopology topo;
  topo.Build(mesh);
  MESHLOD_CHECK_EQ(topo.CountVertices(VertexKind::Interior), 6);
  for (Id v = 0; v < 6; ++v)
  {
    MESHLOD_CHECK_EQ(topo.Valence(mesh, v), 4);
    MESHLOD_CHECK_EQ(topo.VertexTriangles.Count(v), 4);
  }
  // Rows are sorted: vertex 4 (+z) is in triangles 0..3.
  const std::vector<Id> row4(topo.VertexTriangles.Of(4), topo.VertexTriangles.Of(4) + 4);
  MESHLOD_CHECK(row4 == std::vector<Id>({ 0, 1, 2, 3 }));
  // Triangle 0 = (0, 2, 4): edge (0,2) is shared with triangle 4 = (2, 0, 5), edge (2,4) with
  // triangle 1 = (2, 1, 4), edge (4,0) with triangle 3 = (3, 0, 4).
  MESHLOD_CHECK_EQ(topo.EdgeNeighbors[0], 4);
  MESHLOD_CHECK_EQ(topo.EdgeNeighbors[1], 1);
  MESHLOD_CHECK_EQ(topo.EdgeNeighbors[2], 3);
  Id onEdge[4];
  MESHLOD_CHECK_EQ(topo.TrianglesOnEdge(mesh, 0, 2, onEdge, 4), 2);
  MESHLOD_CHECK_EQ(onEdge[0], 0);
  MESHLOD_CHECK_EQ(onEdge[1], 4);
  MESHLOD_CHECK_EQ(topo.TrianglesOnEdge(mesh, 0, 1, onEdge, 4), 0); // opposite corners
  const TriangleTopology::EdgeCounts edges = topo.CountEdges(mesh);
  MESHLOD_CHECK_EQ(edges.Manifold, 12);
  MESHLOD_CHECK_EQ(edges.Boundary, 0);
  MESHLOD_CHECK_EQ(edges.NonManifold, 0);
  MESHLOD_CHECK_EQ(topo.EulerCharacteristic(mesh), 2);
  MESHLOD_CHECK(topo.IsConsistentlyOriented(mesh));
  MESHLOD_CHECK(topo.OrientedWhenBuilt);

  // Flipping one triangle breaks the orientation.
  std::swap(mesh.Triangle(5)[0], mesh.Triangle(5)[1]);
  topo.Build(mesh);
  MESHLOD_CHECK(!topo.IsConsistentlyOriented(mesh));
  MESHLOD_CHECK(!topo.OrientedWhenBuilt);
  MESHLOD_CHECK_EQ(topo.EulerCharacteristic(mesh), 2);
}

void TestGrid()
{
  // 2x2 squares: 9 points, 8 triangles; diagonals run from (i, j) to (i+1, j+1).
  TriangleMesh mesh = ToCore(testing::MakeGrid(2, 2));
  TriangleTopology topo;
  topo.Build(mesh);
  MESHLOD_CHECK_EQ(topo.VertexKinds[4], VertexKind::Interior);
  MESHLOD_CHECK_EQ(topo.CountVertices(VertexKind::Boundary), 8);
  MESHLOD_CHECK_EQ(topo.Valence(mesh, 4), 6); // 1, 3, 5, 7 and the diagonals 0, 8
  MESHLOD_CHECK_EQ(topo.Valence(mesh, 0), 3); // 1, 3, 4
  MESHLOD_CHECK_EQ(topo.Valence(mesh, 2), 2); // 1, 5
  const TriangleTopology::EdgeCounts edges = topo.CountEdges(mesh);
  MESHLOD_CHECK_EQ(edges.Boundary, 8);
  MESHLOD_CHECK_EQ(edges.Manifold, 8);
  MESHLOD_CHECK_EQ(topo.EulerCharacteristic(mesh), 1);
  MESHLOD_CHECK(topo.IsConsistentlyOriented(mesh));
}

void TestTetrahedron()
{
  TriangleMesh mesh = ToCore(testing::MakeTetrahedron());
  TriangleTopology topo;
  topo.Build(mesh);
  for (Id v = 0; v < 4; ++v)
  {
    MESHLOD_CHECK_EQ(topo.Valence(mesh, v), 3);
    MESHLOD_CHECK_EQ(topo.VertexKinds[v], VertexKind::Interior);
  }
  MESHLOD_CHECK_EQ(topo.EulerCharacteristic(mesh), 2);
  MESHLOD_CHECK(topo.IsConsistentlyOriented(mesh));
}

void TestNonManifold()
{
  TriangleMesh mesh = ToCore(testing::MakeNonManifoldEdge());
  TriangleTopology topo;
  topo.Build(mesh);
  MESHLOD_CHECK_EQ(topo.EdgeNeighbors[0], NonManifoldEdge); // edge (0, 1) of triangle 0
  MESHLOD_CHECK_EQ(topo.VertexKinds[0], VertexKind::NonManifold);
  MESHLOD_CHECK_EQ(topo.VertexKinds[1], VertexKind::NonManifold);
  MESHLOD_CHECK_EQ(topo.VertexKinds[2], VertexKind::Boundary);
  const TriangleTopology::EdgeCounts edges = topo.CountEdges(mesh);
  MESHLOD_CHECK_EQ(edges.NonManifold, 1);
  MESHLOD_CHECK_EQ(edges.Boundary, 6);
  MESHLOD_CHECK_EQ(edges.Manifold, 0);

  TriangleMesh bowTie = ToCore(testing::MakeBowTie());
  topo.Build(bowTie);
  MESHLOD_CHECK_EQ(topo.VertexKinds[0], VertexKind::NonManifold);
  MESHLOD_CHECK_EQ(topo.CountVertices(VertexKind::Boundary), 6);
  const TriangleTopology::EdgeCounts bowTieEdges = topo.CountEdges(bowTie);
  MESHLOD_CHECK_EQ(bowTieEdges.Manifold, 2);
  MESHLOD_CHECK_EQ(bowTieEdges.Boundary, 8);
  MESHLOD_CHECK_EQ(topo.Valence(bowTie, 0), 6);

  // Two closed tetrahedra pinched together at point 0: no boundary edge anywhere, yet two
  // separate fans meet at point 0.
  vtkSmartPointer<vtkPolyData> pinched = testing::MakePolyData(
    { 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, -1, 0, 0, 0, -1, 0, 0, 0, -1 },
    { 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3, 0, 4, 5, 0, 5, 6, 0, 6, 4, 4, 6, 5 });
  TriangleMesh twoTetrahedra = ToCore(pinched);
  topo.Build(twoTetrahedra);
  MESHLOD_CHECK_EQ(topo.VertexKinds[0], VertexKind::NonManifold);
  MESHLOD_CHECK_EQ(topo.CountVertices(VertexKind::Interior), 6);
  MESHLOD_CHECK_EQ(topo.CountEdges(twoTetrahedra).Manifold, 12);
  MESHLOD_CHECK_EQ(topo.EulerCharacteristic(twoTetrahedra), 3);
}

void TestHole()
{
  TriangleMesh mesh = ToCore(testing::MakeGridWithHole());
  TriangleTopology topo;
  topo.Build(mesh);
  MESHLOD_CHECK_EQ(mesh.GetNumberOfTriangles(), 24);
  MESHLOD_CHECK_EQ(topo.VertexKinds[12], VertexKind::Unused); // the centre point
  MESHLOD_CHECK_EQ(topo.CountVertices(VertexKind::Boundary), 24);
  const TriangleTopology::EdgeCounts edges = topo.CountEdges(mesh);
  MESHLOD_CHECK_EQ(edges.Boundary, 24); // 16 outside, 8 around the hole
  MESHLOD_CHECK_EQ(edges.Manifold, 24);
  MESHLOD_CHECK_EQ(topo.EulerCharacteristic(mesh), 0); // an annulus

  // The compact boundary flags answer IsBoundaryEdge exactly as the edge neighbours did.
  std::vector<bool> before;
  for (Id t = 0; t < mesh.GetNumberOfTriangles(); ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      before.push_back(topo.IsBoundaryEdge(t, k));
    }
  }
  MESHLOD_CHECK_EQ(std::count(before.begin(), before.end(), true), 24);
  topo.KeepBoundaryFlagsOnly();
  MESHLOD_CHECK(topo.EdgeNeighbors.empty());
  MESHLOD_CHECK_EQ(static_cast<Id>(topo.BoundaryFlags.size()), mesh.GetNumberOfTriangles());
  for (Id t = 0; t < mesh.GetNumberOfTriangles(); ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      MESHLOD_CHECK_EQ(topo.IsBoundaryEdge(t, k), before[3 * t + k]);
    }
  }
  topo.Build(mesh); // a rebuild restores the neighbours
  MESHLOD_CHECK_EQ(topo.EdgeNeighbors.size(), before.size());
  MESHLOD_CHECK(topo.BoundaryFlags.empty());
}

void TestCompaction()
{
  // Delete the two triangles of the top-right square of a 2x2 grid: point 8 is no longer used.
  TriangleMesh mesh = ToCore(testing::MakeGrid(2, 2));
  mesh.Triangle(6)[0] = InvalidId;
  mesh.Triangle(7)[0] = InvalidId;
  TriangleMesh compact;
  CompactionMaps maps;
  CompactMesh(mesh, compact, maps);
  MESHLOD_CHECK_EQ(compact.GetNumberOfTriangles(), 6);
  MESHLOD_CHECK_EQ(compact.GetNumberOfPoints(), 8);
  MESHLOD_CHECK_EQ(maps.PointMap[8], InvalidId);
  MESHLOD_CHECK_EQ(maps.PointMap[7], 7);
  MESHLOD_CHECK_EQ(maps.TriangleMap[6], InvalidId);
  MESHLOD_CHECK(maps.KeptTriangles == std::vector<Id>({ 0, 1, 2, 3, 4, 5 }));
  // Square (0, 1) gives triangles 4 = (3, 4, 7) and 5 = (3, 7, 6); their ids do not change.
  MESHLOD_CHECK_EQ(compact.Triangle(5)[0], 3);
  MESHLOD_CHECK_EQ(compact.Triangle(5)[1], 7);
  MESHLOD_CHECK_EQ(compact.Triangle(5)[2], 6);
  MESHLOD_CHECK_EQ(compact.Point(7)[0], 1.0);
  MESHLOD_CHECK_EQ(compact.Point(7)[1], 2.0);

  // Dropping a middle point renumbers the later ones.
  TriangleMesh fan = ToCore(testing::MakeGrid(2, 1));
  // Keep only triangle 1 = (0, 4, 3): points 1, 2 and 5 go, 3 and 4 become 1 and 2.
  fan.Triangle(0)[0] = InvalidId;
  fan.Triangle(2)[0] = InvalidId;
  fan.Triangle(3)[0] = InvalidId;
  CompactMesh(fan, compact, maps);
  MESHLOD_CHECK(maps.KeptPoints == std::vector<Id>({ 0, 3, 4 }));
  MESHLOD_CHECK_EQ(compact.Triangle(0)[0], 0);
  MESHLOD_CHECK_EQ(compact.Triangle(0)[1], 2);
  MESHLOD_CHECK_EQ(compact.Triangle(0)[2], 1);
}

// The memory hints change neither contents nor sizes: ReserveFresh keeps what a vector holds and
// gives room for n elements; PrepareForWriting on memory already written leaves it as it was
// (a hint that discarded pages, such as MADV_DONTNEED, would zero them).
void TestFreshMemory()
{
  std::vector<std::int32_t> values(1000);
  std::iota(values.begin(), values.end(), 7);
  const std::size_t n = 3 << 20; // 12 MB of int32: room for huge pages inside
  meshlod::ReserveFresh(values, n);
  MESHLOD_CHECK_GE(values.capacity(), n);
  MESHLOD_CHECK_EQ(values.size(), 1000u);
  MESHLOD_CHECK_EQ(values[0], 7);
  MESHLOD_CHECK_EQ(values[999], 1006);
  values.resize(n);
  std::iota(values.begin(), values.end(), -5);
  meshlod::PrepareForWriting(values.data(), n * sizeof(std::int32_t));
  bool intact = true;
  for (std::size_t i = 0; i < n; ++i)
  {
    intact = intact && values[i] == static_cast<std::int32_t>(i) - 5;
  }
  MESHLOD_CHECK(intact);
  // Small requests and capacity already there: nothing moves.
  const std::int32_t* before = values.data();
  meshlod::ReserveFresh(values, n / 2);
  MESHLOD_CHECK(values.data() == before);
  // A vector that grows again gets twice its room, as std::vector's own growth gives: growing
  // one element at a time must not copy everything each time.
  const std::size_t room = values.capacity();
  meshlod::ReserveFresh(values, room + 1);
  MESHLOD_CHECK_GE(values.capacity(), 2 * room);
  MESHLOD_CHECK_EQ(values.size(), n);
  MESHLOD_CHECK_EQ(values[n - 1], static_cast<std::int32_t>(n) - 6);
  std::vector<double> small(10, 1.5);
  meshlod::ReserveFresh(small, 100);
  MESHLOD_CHECK_EQ(small.size(), 10u);
  MESHLOD_CHECK_EQ(small[9], 1.5);
}
// Rows of a mesh large enough for the rows to be built by ranges of vertices in parallel (from
// 65,536 triangles, with more than one thread): every row lists its live triangles in
// increasing order, as one pass in triangle order gives.
void TestLargeRows()
{
  TriangleMesh mesh = ToCore(testing::MakeGrid(200, 200)); // 80,000 triangles
  for (Id t = 0; t < mesh.GetNumberOfTriangles(); t += 7)
  {
    mesh.Triangle(t)[0] = InvalidId;
  }
  std::vector<std::vector<Id>> expected(mesh.GetNumberOfPoints());
  for (Id t = 0; t < mesh.GetNumberOfTriangles(); ++t)
  {
    const Id* tri = mesh.Triangle(t);
    for (int k = 0; tri[0] != InvalidId && k < 3; ++k)
    {
      expected[tri[k]].push_back(t);
    }
  }
  VertexTriangleAdjacency rows;
  rows.Build(mesh);
  bool same = rows.Offsets.size() == expected.size() + 1;
  for (Id v = 0; same && v < mesh.GetNumberOfPoints(); ++v)
  {
    same = std::equal(rows.Triangles.begin() + rows.Begin(v), rows.Triangles.begin() + rows.End(v),
      expected[v].begin(), expected[v].end());
  }
  MESHLOD_CHECK(same);
  MESHLOD_CHECK_EQ(rows.Offsets.back(), 3 * (80000 - (80000 + 6) / 7));
}

// Bounds of a mesh large enough for GetBounds to take them in blocks of points in parallel:
// the lowest and highest coordinates, whichever block holds them.
void TestLargeBounds()
{
  TriangleMesh mesh = ToCore(testing::MakeGrid(200, 200)); // 40,401 points
  const Id points = mesh.GetNumberOfPoints();
  for (Id v = 0; v < points; ++v)
  {
    double* x = mesh.Point(v);
    x[2] = 0.001 * static_cast<double>((v * 7919) % 1000) - 0.3;
  }
  mesh.Point(points - 1)[0] = -5.0; // in the last block
  mesh.Point(20000)[1] = 1e4;       // in a middle block
  mesh.Point(5)[2] = 7.0;            // in the first block
  mesh.Point(3)[1] = -8.0;
  double lo[3], hi[3];
  mesh.GetBounds(lo, hi);
  double expectedLo[3], expectedHi[3];
  std::copy(mesh.Point(0), mesh.Point(0) + 3, expectedLo);
  std::copy(mesh.Point(0), mesh.Point(0) + 3, expectedHi);
  for (Id v = 1; v < points; ++v)
  {
    for (int c = 0; c < 3; ++c)
    {
      expectedLo[c] = std::min(expectedLo[c], mesh.Point(v)[c]);
      expectedHi[c] = std::max(expectedHi[c], mesh.Point(v)[c]);
    }
  }
  MESHLOD_CHECK_EQ(lo[0], -5.0);
  MESHLOD_CHECK_EQ(hi[1], 1e4);
  MESHLOD_CHECK_EQ(hi[2], 7.0);
  MESHLOD_CHECK_EQ(lo[1], -8.0);
  for (int c = 0; c < 3; ++c)
  {
    MESHLOD_CHECK_EQ(lo[c], expectedLo[c]);
    MESHLOD_CHECK_EQ(hi[c], expectedHi[c]);
  }
  MESHLOD_CHECK(lo[2] < -0.29);

  // A NaN coordinate is passed over, as by one pass from point 0, also at the first point of
  // a block (which once emptied the rest of that block's box).
  mesh.Point(16384)[0] = std::numeric_limits<double>::quiet_NaN();
  mesh.Point(16385)[0] = -7.0;
  mesh.GetBounds(lo, hi);
  MESHLOD_CHECK_EQ(lo[0], -7.0);
  MESHLOD_CHECK_EQ(hi[2], 7.0);
}
} // namespace

int TestTriangleMesh(int, char*[])
{
  TestOctahedron();
  TestGrid();
  TestTetrahedron();
  TestNonManifold();
  TestHole();
  TestCompaction();
  TestFreshMemory();
  TestLargeRows();
  TestLargeBounds();
  return meshlod::testing::Result();
}
