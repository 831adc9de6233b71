#include "LinkFan.h"

#include <algorithm>

namespace meshlod
{
namespace
{
// The one-fan test of LinkIsOneFan over n link edges, given how many edges leave and enter the
// vertex edge i leaves from (`degrees(i, leaves, enters)`) and the edge that leaves from where
// edge i ends (`next(i)`, n when none).
template <typename Degrees, typename Next>
bool WalksOneFan(size_t n, Degrees&& degrees, Next&& next)
{
  size_t start = 0;
  int starts = 0;
  for (size_t i = 0; i < n; ++i)
  {
    size_t leaves = 0, enters = 0;
    degrees(i, leaves, enters);
    if (leaves != 1 || enters > 1)
    {
      return false;
    }
    if (enters == 0)
    {
      ++starts;
      start = i;
    }
  }
  if (n == 0 || starts > 1 || (starts == 0 && n < 3))
  {
    return n == 0;
  }
  size_t walked = 1, edge = start;
  for (;;)
  {
    const size_t j = next(edge);
    if (j == n || j == start)
    {
      break;
    }
    edge = j;
    if (++walked > n)
    {
      return false;
    }
  }
  return walked == n;
}

// Whether link edges from[i] -> to[i] form one fan: every link vertex leaves once and enters
// at most once, there is one start (a path) or none (a cycle of at least three edges), and the
// walk from it takes every edge. Short links (the usual few edges) by direct counting, which
// allocates nothing; long ones, around the merged vertex of a large cluster (thousands of
// points, as many link edges), sorted, in n log n.
bool LinkIsOneFan(const std::vector<Id>& from, const std::vector<Id>& to)
{
  const size_t n = from.size();
  if (n <= 32)
  {
    return WalksOneFan(
      n,
      [&](size_t i, size_t& leaves, size_t& enters) {
        for (size_t j = 0; j < n; ++j)
        {
          leaves += from[j] == from[i] ? 1 : 0;
          enters += to[j] == from[i] ? 1 : 0;
        }
      },
      [&](size_t edge) {
        size_t j = 0;
        while (j < n && from[j] != to[edge])
        {
          ++j;
        }
        return j;
      });
  }
  std::vector<std::pair<Id, size_t>> byFrom(n);
  for (size_t i = 0; i < n; ++i)
  {
    byFrom[i] = { from[i], i };
  }
  std::sort(byFrom.begin(), byFrom.end());
  std::vector<Id> sortedTo(to);
  std::sort(sortedTo.begin(), sortedTo.end());
  const auto count = [](const auto& sorted, Id value, auto key) {
    const auto first = std::lower_bound(sorted.begin(), sorted.end(), value,
      [&](const auto& element, Id v) { return key(element) < v; });
    size_t found = 0;
    for (auto it = first; it != sorted.end() && key(*it) == value; ++it)
    {
      ++found;
    }
    return found;
  };
  return WalksOneFan(
    n,
    [&](size_t i, size_t& leaves, size_t& enters) {
      leaves = count(byFrom, from[i], [](const std::pair<Id, size_t>& e) { return e.first; });
      enters = count(sortedTo, from[i], [](Id v) { return v; });
    },
    [&](size_t edge) {
      const auto it = std::lower_bound(
        byFrom.begin(), byFrom.end(), std::make_pair(to[edge], static_cast<size_t>(0)));
      return it == byFrom.end() || it->first != to[edge] ? n : it->second;
    });
}

} // namespace

// Whether a merged vertex's link edges from[i] -> to[i], without regard to direction, have a
// given shape: no link edge twice, all connected, `ends` link vertices on `endDegree` link
// edges and every other on two. On a curve where k > 2 sheets meet (as between the regions of
// a segmented volume) the sheets' orientations need not agree: k paths between the vertex's two
// neighbours on the curve are ends = 2, endDegree = k. One fan on a surface whose orientation
// is not consistent: a path (ends = 2, endDegree = 1) or a cycle of at least three edges
// (ends = 0).
bool LinkHasShape(const std::vector<Id>& from, const std::vector<Id>& to, int endDegree, int ends)
{
  const size_t n = from.size();
  std::vector<std::pair<Id, Id>> edges(n);
  std::vector<Id> vertices;
  for (size_t i = 0; i < n; ++i)
  {
    edges[i] = { std::min(from[i], to[i]), std::max(from[i], to[i]) };
    vertices.push_back(from[i]);
    vertices.push_back(to[i]);
  }
  std::sort(edges.begin(), edges.end());
  if (n == 0 || (ends == 0 && n < 3) ||
    std::adjacent_find(edges.begin(), edges.end()) != edges.end())
  {
    return false;
  }
  std::sort(vertices.begin(), vertices.end());
  int atEnds = 0, others = 0;
  ForEachRun(vertices, [&](int degree) {
    atEnds += ends > 0 && degree == endDegree ? 1 : 0;
    others += (ends == 0 || degree != endDegree) && degree != 2 ? 1 : 0;
  });
  if (atEnds != ends || others != 0)
  {
    return false;
  }
  // Connected: grow from one vertex over the link edges.
  std::vector<Id> reached(1, vertices.front());
  for (bool grew = true; grew;)
  {
    grew = false;
    for (const auto& e : edges)
    {
      const bool a = std::find(reached.begin(), reached.end(), e.first) != reached.end();
      const bool b = std::find(reached.begin(), reached.end(), e.second) != reached.end();
      if (a != b)
      {
        reached.push_back(a ? e.second : e.first);
        grew = true;
      }
    }
  }
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  return reached.size() == vertices.size();
}

// Whether two of the triangles around `members` use the same directed edge a -> b: their
// orientation is not consistent there (across a Moebius strip's or Boy's surface's seam), and
// one fan's link edges need not follow each other in direction. Local: only the stars are read.
bool HasRepeatedDirectedEdge(const Id* triangles, const VertexTriangleAdjacency& adjacency,
  const std::vector<Id>& members, std::vector<Id>& around, std::vector<std::pair<Id, Id>>& edges)
{
  around.clear();
  for (const Id m : members)
  {
    for (Id i = adjacency.Begin(m); i < adjacency.End(m); ++i)
    {
      around.push_back(adjacency.Triangles[i]);
    }
  }
  std::sort(around.begin(), around.end());
  around.erase(std::unique(around.begin(), around.end()), around.end());
  edges.clear();
  for (const Id t : around)
  {
    const Id* tri = triangles + 3 * static_cast<size_t>(t);
    for (int k = 0; k < 3; ++k)
    {
      edges.emplace_back(tri[k], tri[(k + 1) % 3]);
    }
  }
  std::sort(edges.begin(), edges.end());
  return std::adjacent_find(edges.begin(), edges.end()) != edges.end();
}

// Whether the vertex `merged` (a class of the union-find) has one fan: the triangles around its
// members, with corners replaced by their classes and degenerate ones left out, give link edges
// u -> w that form one cycle of at least three edges or one path, each vertex leaving and
// entering at most once. Those link edges are left in `from` and `to`.
bool HasOneFan(const Id* triangles, const VertexTriangleAdjacency& adjacency,
  std::vector<Id>& parent, const std::vector<Id>& members, Id merged, std::vector<Id>& from,
  std::vector<Id>& to)
{
  from.clear();
  to.clear();
  for (const Id m : members)
  {
    for (Id i = adjacency.Begin(m); i < adjacency.End(m); ++i)
    {
      const Id* tri = triangles + 3 * static_cast<size_t>(adjacency.Triangles[i]);
      const Id c[3] = { FindRoot(parent, tri[0]), FindRoot(parent, tri[1]),
        FindRoot(parent, tri[2]) };
      if (c[0] == c[1] || c[1] == c[2] || c[2] == c[0])
      {
        continue; // gone
      }
      const int k = c[0] == merged ? 0 : (c[1] == merged ? 1 : 2);
      if (tri[k] != m)
      {
        continue; // listed under the member at that corner
      }
      from.push_back(c[(k + 1) % 3]);
      to.push_back(c[(k + 2) % 3]);
    }
  }
  return LinkIsOneFan(from, to);
}

} // namespace meshlod
