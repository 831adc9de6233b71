// The VTK-free core of vtkVertexClusterOctree: quadric placement, the cluster tree's invariants,
// nesting of the levels at the node level, and the texture atlas layout.
#include "Core/ClusterTree.h"
#include "Core/OctreeClustering.h"
#include "Core/Quadric.h"
#include "Core/TextureAtlas.h"
#include "MeshLODInputMesh.h"
#include "MeshLODTestCheck.h"
#include "MeshLODTestMeshes.h"

#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkTriangleFilter.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>

namespace
{
using namespace meshlod;

bool Read(vtkPolyData* poly, InputMesh& mesh)
{
  vtkNew<vtkTriangleFilter> caller;
  return ReadInputMesh(poly, caller, mesh) == InputStatus::Valid;
}

//------------------------------------------------------------------------------
void TestPlacement()
{
  // Three planes through (1, 2, 3): the corner, whatever the centre.
  Quadric q;
  const double corner[3] = { 1, 2, 3 };
  const double normals[3][3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
  for (const auto& n : normals)
  {
    q.AddPlane(n, corner, 2.0);
  }
  MESHLOD_CHECK_EQ(q.Weight(), 6.0);
  double x[3];
  const double centre[3] = { -5, 7, 0.5 };
  MinimizeQuadric(q, centre, 1e-3, x);
  for (int c = 0; c < 3; ++c)
  {
    MESHLOD_CHECK_LE(std::abs(x[c] - corner[c]), 1e-12);
  }
  MESHLOD_CHECK_LE(q.Evaluate(x), 1e-20);
  // One plane z = 3: the centre projected onto it (x, y stay where they were).
  Quadric flat;
  flat.AddPlane(normals[2], corner, 1.0);
  MinimizeQuadric(flat, centre, 1e-3, x);
  MESHLOD_CHECK_EQ(x[0], -5.0);
  MESHLOD_CHECK_EQ(x[1], 7.0);
  MESHLOD_CHECK_LE(std::abs(x[2] - 3.0), 1e-12);
  // Two planes meeting at a very small angle: a full solve would run to their line (y = 2);
  // the near-null direction is left at the centre instead.
  Quadric wedge;
  const double tilted[3] = { 0, std::sin(1e-3), std::cos(1e-3) };
  wedge.AddPlane(normals[2], corner, 1.0);
  wedge.AddPlane(tilted, corner, 1.0);
  MinimizeQuadric(wedge, centre, 1e-3, x);
  MESHLOD_CHECK_EQ(x[0], -5.0);
  MESHLOD_CHECK_LE(std::abs(x[1] - 7.0), 0.01);
  MESHLOD_CHECK_LE(wedge.Evaluate(x), 2e-5); // (5 * sin(1e-3))^2 / 2 from the tilted plane
  // Triangle and boundary-edge quadrics: the distances they measure.
  const double a[3] = { 0, 0, 0 }, b[3] = { 2, 0, 0 }, c[3] = { 0, 2, 0 };
  Quadric face;
  double n[3];
  TriangleQuadric(a, b, c, face, n);
  MESHLOD_CHECK_EQ(n[2], 4.0);
  MESHLOD_CHECK_LE(std::abs(face.Weight() - 2.0), 1e-12); // the area
  const double above[3] = { 0.3, 0.3, 0.5 };
  MESHLOD_CHECK_LE(std::abs(face.Evaluate(above) - 2.0 * 0.25), 1e-12);
  Quadric edge;
  BoundaryEdgeQuadric(a, b, n, 1.0, edge);
  MESHLOD_CHECK_LE(std::abs(edge.Evaluate(above) - 4.0 * 0.09), 1e-12); // |e|^2 * y^2
}

//------------------------------------------------------------------------------
// Tree invariants: ranges, counts, cells, connectivity, e1 against a direct computation.
void TestTree(vtkPolyData* poly)
{
  InputMesh in;
  MESHLOD_CHECK(Read(poly, in));
  OctreeClusteringOptions options;
  OctreeClustering clustering(in.Mesh, in.Topology, options);
  clustering.BuildTree();
  const ClusterTree& tree = clustering.GetTree();
  const Id nv = tree.NV;
  const Id ni = tree.NumberOfInternalNodes();
  MESHLOD_CHECK_EQ(nv, in.Mesh.GetNumberOfPoints());
  MESHLOD_CHECK_GT(ni, 0);
  MESHLOD_CHECK_LT(ni, nv);
  MESHLOD_CHECK_LE(clustering.CheckNodeQuadrics(500), 1e-7);

  // Order is a permutation and PosOf its inverse.
  std::vector<Id> seen(nv, 0);
  for (Id pos = 0; pos < nv; ++pos)
  {
    ++seen[tree.Order[pos]];
    MESHLOD_CHECK_EQ(tree.PosOf[tree.Order[pos]], pos);
  }
  MESHLOD_CHECK_EQ(std::count(seen.begin(), seen.end(), 1), static_cast<long>(nv));

  // Parents come after their children, are no shallower, and their ranges hold the child's.
  std::vector<Id> childCount(ni, 0);
  Id badOrder = 0, badRange = 0, badDepth = 0;
  for (Id node = 0; node < nv + ni; ++node)
  {
    const Id parent = tree.Parent(node);
    if (parent == InvalidId)
    {
      continue;
    }
    badOrder += parent > node ? 0 : 1;
    childCount[parent - nv] += tree.Count(node);
    badRange +=
      (tree.Position(node) >= tree.Position(parent) &&
        tree.Position(node) + tree.Count(node) <= tree.Position(parent) + tree.Count(parent))
      ? 0
      : 1;
    if (node >= nv)
    {
      badDepth += tree.Internal(node).Depth > tree.Internal(parent).Depth ? 0 : 1;
    }
  }
  MESHLOD_CHECK_EQ(badOrder, 0);
  MESHLOD_CHECK_EQ(badRange, 0);
  MESHLOD_CHECK_EQ(badDepth, 0);
  Id badCount = 0;
  for (Id i = 0; i < ni; ++i)
  {
    badCount += childCount[i] == tree.Nodes[i].Count ? 0 : 1;
  }
  MESHLOD_CHECK_EQ(badCount, 0);

  // The bottom tier's nodes, cell by cell: each node's parent lies in its own cell's range or in
  // the top tier (the parallel passes over cells rely on it).
  const std::vector<Id>& cellOffsets = tree.CellNodeOffsets;
  MESHLOD_CHECK_GT(cellOffsets.size(), 2u);
  MESHLOD_CHECK_EQ(cellOffsets.front(), 0);
  MESHLOD_CHECK_LE(cellOffsets.back(), ni);
  Id badCell = 0;
  for (size_t c = 0; c + 1 < cellOffsets.size(); ++c)
  {
    badCell += cellOffsets[c] <= cellOffsets[c + 1] ? 0 : 1;
    for (Id i = cellOffsets[c]; i < cellOffsets[c + 1]; ++i)
    {
      const Id parent = tree.Nodes[i].Parent;
      const bool sameCell = parent != InvalidId && parent - nv >= cellOffsets[c] &&
        parent - nv < cellOffsets[c + 1];
      const bool top = parent != InvalidId && parent - nv >= cellOffsets.back();
      badCell += parent == InvalidId || sameCell || top ? 0 : 1;
    }
  }
  MESHLOD_CHECK_EQ(badCell, 0);

  // Every node: its vertices share one cell of its depth and are connected inside the node.
  const VertexTriangleAdjacency& adj = in.Topology.VertexTriangles;
  Id outsideCell = 0, disconnected = 0;
  for (Id i = 0; i < ni; i += std::max<Id>(1, ni / 300))
  {
    const Id node = nv + i;
    const Id first = tree.Position(node), count = tree.Count(node);
    for (Id pos = first; pos < first + count; ++pos)
    {
      outsideCell +=
        tree.CommonDepth(tree.Order[first], tree.Order[pos]) >= tree.Nodes[i].Depth ? 0 : 1;
    }
    std::vector<Id> stack(1, tree.Order[first]);
    std::set<Id> reached(stack.begin(), stack.end());
    while (!stack.empty())
    {
      const Id v = stack.back();
      stack.pop_back();
      for (Id j = adj.Begin(v); j < adj.End(v); ++j)
      {
        for (int k = 0; k < 3; ++k)
        {
          const Id w = in.Mesh.Triangle(adj.Triangles[j])[k];
          if (tree.Contains(node, w) && reached.insert(w).second)
          {
            stack.push_back(w);
          }
        }
      }
    }
    disconnected += static_cast<Id>(reached.size()) == count ? 0 : 1;
  }
  MESHLOD_CHECK_EQ(outsideCell, 0);
  MESHLOD_CHECK_EQ(disconnected, 0);

  // Levels: every point's node lies inside its target's node (the clusters nest), and the
  // levels' triangle counts fall.
  Id previousTriangles = in.Mesh.GetNumberOfTriangles();
  std::vector<Id> previousNodes(nv);
  std::iota(previousNodes.begin(), previousNodes.end(), 0);
  const double diagonal = tree.Size;
  for (const double epsilon : { 2e-4, 1e-3, 5e-3 })
  {
    ClusterLevel level;
    MESHLOD_CHECK(clustering.MakeLevel(epsilon * diagonal, level));
    MESHLOD_CHECK_LT(level.Mesh.GetNumberOfTriangles(), previousTriangles);
    MESHLOD_CHECK_LE(level.EstimatedError, epsilon * diagonal);
    Id outside = 0;
    for (size_t p = 0; p < previousNodes.size(); ++p)
    {
      const Id child = previousNodes[p];
      const Id parent = level.PointNode[level.Target[p]];
      const bool inside = tree.Position(child) >= tree.Position(parent) &&
        tree.Position(child) + tree.Count(child) <= tree.Position(parent) + tree.Count(parent);
      // A cluster whose triangles all vanished hands its points to a neighbour.
      outside += inside ? 0 : 1;
    }
    std::cout << "  epsilon " << epsilon << ": " << level.Mesh.GetNumberOfTriangles()
              << " triangles, points handed to a neighbour " << outside << "\n";
    MESHLOD_CHECK_LE(outside, static_cast<Id>(previousNodes.size() / 200));
    // Every point's vertex count is its node's.
    Id badCounts = 0;
    for (Id j = 0; j < level.Mesh.GetNumberOfPoints(); ++j)
    {
      badCounts += level.PointVertexCount[j] == tree.Count(level.PointNode[j]) ? 0 : 1;
    }
    MESHLOD_CHECK_EQ(badCounts, 0);
    previousNodes = level.PointNode;
    previousTriangles = level.Mesh.GetNumberOfTriangles();
  }
}

//------------------------------------------------------------------------------
void TestAtlas()
{
  InputMesh in;
  MESHLOD_CHECK(Read(testing::MakeIcosphere(3), in));
  const TriangleMesh& mesh = in.Mesh;
  TextureAtlas atlas;
  BuildTextureAtlas(mesh, 100, atlas);
  MESHLOD_CHECK_EQ(atlas.Resolution, 128);
  // Blocks: powers of two, inside the texture, disjoint.
  std::vector<unsigned char> used(static_cast<size_t>(atlas.Resolution) * atlas.Resolution, 0);
  Id overlap = 0, outside = 0, paired = 0;
  for (const TextureAtlas::Block& block : atlas.Blocks)
  {
    MESHLOD_CHECK_GE(block.Size, 2);
    MESHLOD_CHECK_EQ(block.Size & (block.Size - 1), 0);
    outside +=
      (block.X + block.Size <= atlas.Resolution && block.Y + block.Size <= atlas.Resolution) ? 0
                                                                                             : 1;
    for (Id y = block.Y; y < std::min(atlas.Resolution, block.Y + block.Size); ++y)
    {
      for (Id x = block.X; x < std::min(atlas.Resolution, block.X + block.Size); ++x)
      {
        overlap += used[y * atlas.Resolution + x]++ ? 1 : 0;
      }
    }
    paired += block.Upper != InvalidId ? 1 : 0;
  }
  MESHLOD_CHECK_EQ(overlap, 0);
  MESHLOD_CHECK_EQ(outside, 0);
  MESHLOD_CHECK_GT(2 * paired, static_cast<Id>(atlas.Blocks.size())); // most triangles pair up
  // Every triangle: a right isosceles half of its block, corners on split copies of its points.
  Id badShape = 0, badPoint = 0, badShared = 0;
  for (Id t = 0; t < mesh.GetNumberOfTriangles(); ++t)
  {
    const TextureAtlas::Block& block = atlas.Blocks[atlas.TriangleBlock[t]];
    const Id s = block.Size - 1;
    std::set<std::pair<Id, Id>> corners;
    for (int k = 0; k < 3; ++k)
    {
      const Id x = atlas.CornerTexel[6 * t + 2 * k] - block.X;
      const Id y = atlas.CornerTexel[6 * t + 2 * k + 1] - block.Y;
      corners.insert({ x, y });
      badPoint += atlas.SplitPoints[atlas.CornerPoint[3 * t + k]] == mesh.Triangle(t)[k] ? 0 : 1;
    }
    const std::set<std::pair<Id, Id>> lower = { { 0, 0 }, { s, 0 }, { 0, s } };
    const std::set<std::pair<Id, Id>> upper = { { s, s }, { s, 0 }, { 0, s } };
    badShape += (corners == (block.Lower == t ? lower : upper)) ? 0 : 1;
    if (block.Upper == t)
    {
      // The diagonal's two ends are the same split points in both triangles.
      std::set<Id> mine, theirs;
      for (int k = 0; k < 3; ++k)
      {
        mine.insert(atlas.CornerPoint[3 * t + k]);
        theirs.insert(atlas.CornerPoint[3 * block.Lower + k]);
      }
      std::vector<Id> common;
      std::set_intersection(
        mine.begin(), mine.end(), theirs.begin(), theirs.end(), std::back_inserter(common));
      badShared += common.size() == 2 ? 0 : 1;
    }
  }
  MESHLOD_CHECK_EQ(badShape, 0);
  MESHLOD_CHECK_EQ(badPoint, 0);
  MESHLOD_CHECK_EQ(badShared, 0);
  // Too small a texture grows to hold every block.
  TextureAtlas tiny;
  BuildTextureAtlas(mesh, 16, tiny);
  MESHLOD_CHECK_GE(tiny.Resolution * tiny.Resolution, 4 * static_cast<Id>(tiny.Blocks.size()));
}
} // namespace

int TestVertexClusterOctreeCore(int, char*[])
{
  TestPlacement();
  TestTree(testing::MakeIsosurface(testing::Field::Metaballs, 40));
  TestTree(testing::MakeIsosurface(testing::Field::Gyroid, 30));
  TestAtlas();
  return meshlod::testing::Result();
}
