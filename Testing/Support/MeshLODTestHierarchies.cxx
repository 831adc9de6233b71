#include "MeshLODTestHierarchies.h"

#include "Core/TriangleMesh.h"
#include "MeshLODHierarchy.h"
#include "MeshLODInputMesh.h"

#include "vtkAlgorithm.h"
#include "vtkCellArray.h"
#include "vtkCompositeDataSet.h"
#include "vtkInformation.h"
#include "vtkMath.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkTriangleFilter.h"

#include <algorithm>
#include <array>
#include <numeric>

namespace meshlod
{
namespace testing
{
namespace
{
void Normal(const double* a, const double* b, const double* c, double n[3])
{
  const double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  const double v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
  vtkMath::Cross(u, v, n);
}

double Area(const TriangleMesh& mesh, Id t)
{
  const Id* tri = mesh.Triangle(t);
  double n[3];
  Normal(mesh.Point(tri[0]), mesh.Point(tri[1]), mesh.Point(tri[2]), n);
  return 0.5 * vtkMath::Norm(n);
}

// The vertices joined to v by an edge.
void Neighbors(const TriangleMesh& mesh, const TriangleTopology& topo, Id v, std::vector<Id>& out)
{
  out.clear();
  const VertexTriangleAdjacency& adj = topo.VertexTriangles;
  for (Id i = adj.Begin(v); i < adj.End(v); ++i)
  {
    const Id* tri = mesh.Triangle(adj.Triangles[i]);
    for (int k = 0; k < 3; ++k)
    {
      if (tri[k] != v)
      {
        out.push_back(tri[k]);
      }
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

struct Collapse
{
  std::array<Id, 3> Corners;
  std::array<Id, 4> Removed; // the triangle and its three edge neighbours
  double Point[3];
};

// One independent-set pass: the collapses of the next level, in rank order.
std::vector<Collapse> ChooseCollapses(
  const TriangleMesh& mesh, const TriangleTopology& topo, double maximumFraction)
{
  const Id nt = mesh.GetNumberOfTriangles();
  std::vector<double> area(nt);
  for (Id t = 0; t < nt; ++t)
  {
    area[t] = Area(mesh, t);
  }
  std::vector<Id> order(nt);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](Id a, Id b) { return area[a] < area[b]; });

  const Id budget = static_cast<Id>(maximumFraction * nt / 4.0);
  std::vector<std::uint8_t> locked(mesh.GetNumberOfPoints(), 0);
  std::vector<Collapse> chosen;
  std::vector<Id> ring, neighbors;
  for (const Id t : order)
  {
    if (static_cast<Id>(chosen.size()) >= budget)
    {
      break;
    }
    const Id* tri = mesh.Triangle(t);
    Collapse c;
    c.Corners = { tri[0], tri[1], tri[2] };
    c.Removed[0] = t;
    bool ok = true;
    std::array<Id, 3> apex{};
    for (int k = 0; k < 3 && ok; ++k)
    {
      ok = !locked[tri[k]] && topo.VertexKinds[tri[k]] == VertexKind::Interior;
      const Id nb = topo.EdgeNeighbors[3 * static_cast<size_t>(t) + k];
      ok = ok && nb >= 0;
      if (ok)
      {
        c.Removed[k + 1] = nb;
        const Id* other = mesh.Triangle(nb);
        for (int j = 0; j < 3; ++j)
        {
          if (other[j] != tri[k] && other[j] != tri[(k + 1) % 3])
          {
            apex[k] = other[j];
          }
        }
      }
    }
    if (!ok || apex[0] == apex[1] || apex[1] == apex[2] || apex[2] == apex[0])
    {
      continue;
    }
    // The ring: every vertex next to a corner. The apexes touch exactly two corners, every
    // other ring vertex exactly one; the apexes keep valence >= 3 after losing one edge.
    ring.clear();
    for (const Id v : c.Corners)
    {
      Neighbors(mesh, topo, v, neighbors);
      for (const Id w : neighbors)
      {
        if (w != c.Corners[0] && w != c.Corners[1] && w != c.Corners[2])
        {
          ring.push_back(w);
        }
      }
    }
    std::sort(ring.begin(), ring.end());
    for (size_t i = 0; i < ring.size() && ok; ++i)
    {
      const Id w = ring[i];
      const size_t count = std::count(ring.begin(), ring.end(), w);
      const bool isApex = w == apex[0] || w == apex[1] || w == apex[2];
      ok = !locked[w] && count == (isApex ? 2u : 1u) && (!isApex || topo.Valence(mesh, w) >= 4);
    }
    ok = ok && std::unique(ring.begin(), ring.end()) - ring.begin() >= 3;
    if (!ok)
    {
      continue;
    }
    // Collapse point: the centroid. No surviving triangle of the stencil may flip.
    for (int j = 0; j < 3; ++j)
    {
      c.Point[j] = (mesh.Point(tri[0])[j] + mesh.Point(tri[1])[j] + mesh.Point(tri[2])[j]) / 3.0;
    }
    for (const Id v : c.Corners)
    {
      const VertexTriangleAdjacency& adj = topo.VertexTriangles;
      for (Id i = adj.Begin(v); i < adj.End(v) && ok; ++i)
      {
        const Id s = adj.Triangles[i];
        if (std::find(c.Removed.begin(), c.Removed.end(), s) != c.Removed.end())
        {
          continue;
        }
        const Id* st = mesh.Triangle(s);
        const double* p[3] = { mesh.Point(st[0]), mesh.Point(st[1]), mesh.Point(st[2]) };
        double before[3], after[3];
        Normal(p[0], p[1], p[2], before);
        p[CornerOf(st, v)] = c.Point;
        Normal(p[0], p[1], p[2], after);
        ok = vtkMath::Dot(before, after) > 0.0;
      }
    }
    if (!ok)
    {
      continue;
    }
    for (const Id v : c.Corners)
    {
      locked[v] = 1;
    }
    for (const Id w : ring)
    {
      locked[w] = 1;
    }
    chosen.push_back(c);
  }
  return chosen;
}

// The next level from the chosen collapses (points renumbered in increasing old id, a collapse
// point taking the place of its lowest corner).
LevelData ApplyCollapses(const TriangleMesh& mesh, const std::vector<Collapse>& collapses,
  const std::vector<Id>& levelZeroTriangle)
{
  const Id np = mesh.GetNumberOfPoints();
  const Id nt = mesh.GetNumberOfTriangles();
  std::vector<Id> collapseOf(np, InvalidId);
  std::vector<std::uint8_t> removed(nt, 0);
  for (size_t r = 0; r < collapses.size(); ++r)
  {
    for (const Id v : collapses[r].Corners)
    {
      collapseOf[v] = static_cast<Id>(r);
    }
    for (const Id t : collapses[r].Removed)
    {
      removed[t] = 1;
    }
  }
  LevelData level;
  level.Target.assign(np, InvalidId);
  level.Rank.assign(np, -1);
  level.Sources.Clear();
  std::vector<Id> newOfCollapse(collapses.size(), InvalidId);
  const float one = 1.0f;
  const float third[3] = { 1.0f / 3, 1.0f / 3, 1.0f / 3 };
  for (Id p = 0; p < np; ++p)
  {
    const Id r = collapseOf[p];
    if (r == InvalidId)
    {
      level.Target[p] = level.Mesh.GetNumberOfPoints();
      level.Mesh.Points.insert(level.Mesh.Points.end(), mesh.Point(p), mesh.Point(p) + 3);
      level.Sources.Add(&p, &one, 1);
      continue;
    }
    level.Rank[p] = r;
    if (newOfCollapse[r] == InvalidId)
    {
      newOfCollapse[r] = level.Mesh.GetNumberOfPoints();
      const Collapse& c = collapses[r];
      level.Mesh.Points.insert(level.Mesh.Points.end(), c.Point, c.Point + 3);
      level.Sources.Add(c.Corners.data(), third, 3);
    }
    level.Target[p] = newOfCollapse[r];
  }
  for (Id t = 0; t < nt; ++t)
  {
    if (removed[t])
    {
      continue;
    }
    for (int k = 0; k < 3; ++k)
    {
      level.Mesh.Triangles.push_back(level.Target[mesh.Triangle(t)[k]]);
    }
    level.LevelZeroTriangle.push_back(levelZeroTriangle[t]);
  }
  return level;
}
} // namespace

//------------------------------------------------------------------------------
vtkSmartPointer<vtkMultiBlockDataSet> MakeCollapseHierarchy(
  vtkPolyData* mesh, const CollapseHierarchyOptions& options)
{
  vtkNew<vtkTriangleFilter> reporter; // ReadInputMesh reports its warnings on an algorithm
  InputMesh input;
  auto hierarchy = vtkSmartPointer<vtkMultiBlockDataSet>::New();
  if (ReadInputMesh(mesh, reporter, input) != InputStatus::Valid)
  {
    return hierarchy;
  }
  HierarchyBuilder builder;
  builder.SetLevelZero(input, vtkAlgorithm::DEFAULT_PRECISION);
  TriangleMesh current = input.Mesh;
  TriangleTopology topology = input.Topology;
  std::vector<Id> levelZeroTriangle(current.GetNumberOfTriangles());
  std::iota(levelZeroTriangle.begin(), levelZeroTriangle.end(), 0);
  while (builder.GetNumberOfLevels() < options.MaximumLevels)
  {
    const std::vector<Collapse> collapses =
      ChooseCollapses(current, topology, options.MaximumFraction);
    if (collapses.empty())
    {
      break;
    }
    LevelData level = ApplyCollapses(current, collapses, levelZeroTriangle);
    current = level.Mesh; // AppendLevel consumes the level
    levelZeroTriangle = level.LevelZeroTriangle;
    builder.AppendLevel(std::move(level));
    topology.Build(current);
  }
  if (options.MeasureErrors)
  {
    builder.MeasureLevelErrors();
  }
  builder.Finish(hierarchy);
  return hierarchy;
}

//------------------------------------------------------------------------------
TriangleMesh ToTriangleMesh(vtkPolyData* poly)
{
  TriangleMesh mesh;
  mesh.Points.resize(3 * static_cast<size_t>(poly->GetNumberOfPoints()));
  for (vtkIdType p = 0; p < poly->GetNumberOfPoints(); ++p)
  {
    poly->GetPoint(p, mesh.Point(static_cast<Id>(p)));
  }
  vtkCellArray* polys = poly->GetPolys();
  vtkIdType n;
  const vtkIdType* ids;
  for (polys->InitTraversal(); polys->GetNextCell(n, ids);)
  {
    for (vtkIdType k = 0; k < n; ++k)
    {
      mesh.Triangles.push_back(static_cast<Id>(ids[k]));
    }
  }
  return mesh;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkMultiBlockDataSet> GatherLevels(const std::vector<vtkPolyData*>& levels)
{
  auto hierarchy = vtkSmartPointer<vtkMultiBlockDataSet>::New();
  hierarchy->SetNumberOfBlocks(static_cast<unsigned int>(levels.size()));
  for (size_t i = 0; i < levels.size(); ++i)
  {
    const auto block = static_cast<unsigned int>(i);
    hierarchy->SetBlock(block, levels[i]);
    hierarchy->GetMetaData(block)->Set(
      vtkCompositeDataSet::NAME(), LevelBlockName(static_cast<int>(i)).c_str());
  }
  return hierarchy;
}

} // namespace testing
} // namespace meshlod
