#include "CollapseSchedule.h"
#include "GroupByKey.h"
#include "MergedLink.h"
#include "Vector3.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <array>
#include <functional>
#include <limits>
#include <utility>

namespace meshlod
{
namespace
{
constexpr Id Unassigned = -1;
// A collapse of m points tries at most max(1, TestBudget / m) next points per step (see Build).
constexpr size_t TestBudget = 16384;
// The points of collapses left waiting at the end join interleaved when together they number at
// most this many (each step may test up to TestBudget / m candidates, m the group's largest
// collapse), else one collapse after the other.
constexpr size_t InterleavedGroupPoints = 2048;
// A triangle faces a direction m when its normal n has n . m > FacingTolerance |m|^2 (both are
// twice-area vectors): three corners on a line up to rounding do not.
constexpr double FacingTolerance = 1e-12;

// Union-find over points, for the points settled on one target (they are one vertex then).
Id Find(std::vector<Id>& parent, Id p)
{
  while (parent[p] != p)
  {
    parent[p] = parent[parent[p]];
    p = parent[p];
  }
  return p;
}

// Calls f(length) for each run of equal values in the sorted `values`.
template <typename F>
void ForEachRun(const std::vector<Id>& values, F&& f)
{
  for (size_t i = 0; i < values.size();)
  {
    size_t j = i;
    while (j < values.size() && values[j] == values[i])
    {
      ++j;
    }
    f(static_cast<int>(j - i));
    i = j;
  }
}

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
      const Id c[3] = { Find(parent, tri[0]), Find(parent, tri[1]), Find(parent, tri[2]) };
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

// Moving points sorted by collapse: (rank, -1 last), then target, then id.
std::vector<Id> SortMovingPoints(
  Id numberOfPoints, const Id* target, const std::int64_t* rank, const std::uint8_t* atTarget)
{
  std::vector<Id> moving;
  for (Id p = 0; p < numberOfPoints; ++p)
  {
    if (!atTarget[p])
    {
      moving.push_back(p);
    }
  }
  auto key = [&](Id p) { return rank[p] < 0 ? std::numeric_limits<std::int64_t>::max() : rank[p]; };
  std::sort(moving.begin(), moving.end(), [&](Id a, Id b) {
    const std::int64_t ka = key(a), kb = key(b);
    if (ka != kb)
    {
      return ka < kb;
    }
    if (target[a] != target[b])
    {
      return target[a] < target[b];
    }
    return a < b;
  });
  return moving;
}

// Ids in increasing order, each at most once, with a flag per possible id: the candidates of a
// step, kept up to date as points settle instead of listed again.
struct SortedIds
{
  std::vector<Id> Items;
  std::vector<std::uint8_t> In; // per id

  void Add(Id i)
  {
    if (!this->In[i])
    {
      this->In[i] = 1;
      this->Items.insert(std::lower_bound(this->Items.begin(), this->Items.end(), i), i);
    }
  }
  void Remove(Id i)
  {
    if (this->In[i])
    {
      this->In[i] = 0;
      this->Items.erase(std::lower_bound(this->Items.begin(), this->Items.end(), i));
    }
  }
  void Clear()
  {
    for (const Id i : this->Items)
    {
      this->In[i] = 0;
    }
    this->Items.clear();
  }
};
} // namespace

//------------------------------------------------------------------------------
void CollapseSchedule::Build(const Id* triangles, Id numberOfTriangles, Id numberOfPoints,
  const Id* target, const std::int64_t* rank, const std::uint8_t* atTarget,
  const double* positions, const double* targetPositions, bool waitForFolds)
{
  this->Step.assign(numberOfPoints, Unassigned);
  this->Order.clear();
  this->WaitedForFolds = false;
  for (Id p = 0; p < numberOfPoints; ++p)
  {
    if (atTarget[p])
    {
      this->Step[p] = 0;
    }
  }
  Id numberOfTargets = 0;
  for (Id p = 0; p < numberOfPoints; ++p)
  {
    numberOfTargets = std::max(numberOfTargets, target[p] + 1);
  }
  std::vector<Id> targetOffsets, targetPoints; // the points of each target, in increasing id
  GroupByKey(
    static_cast<size_t>(numberOfTargets),
    [&](auto&& emit) {
      for (Id p = 0; p < numberOfPoints; ++p)
      {
        emit(target[p], p);
      }
    },
    targetOffsets, targetPoints);
  VertexTriangleAdjacency adjacency;
  adjacency.Build(triangles, numberOfTriangles, numberOfPoints);

  const std::vector<Id> moving = SortMovingPoints(numberOfPoints, target, rank, atTarget);
  this->Order.reserve(moving.size());

  // The merges replayed with a union-find: the points settled on one target are one vertex.
  std::vector<Id> parent(numberOfPoints);
  for (Id p = 0; p < numberOfPoints; ++p)
  {
    parent[p] = p;
  }
  std::vector<Id> settledOn(numberOfTargets, Unassigned); // a settled point of each target
  for (Id p = 0; p < numberOfPoints; ++p)
  {
    if (this->Step[p] == 0)
    {
      const Id t = target[p];
      if (settledOn[t] == Unassigned)
      {
        settledOn[t] = p;
      }
      parent[Find(parent, p)] = Find(parent, settledOn[t]);
    }
  }
  // Per target, the sheets meeting at the one of its points on a curve where more than two
  // meet (the most triangles on one edge of a point), else 1; 0 until asked for (only when a
  // step fails the one-fan test, so that a manifold mesh never counts them).
  std::vector<int> sheetsOf(numberOfTargets, 0);
  std::vector<Id> neighbours;
  auto countSheets = [&](Id p) {
    neighbours.clear();
    for (Id i = adjacency.Begin(p); i < adjacency.End(p); ++i)
    {
      const Id* tri = triangles + 3 * static_cast<size_t>(adjacency.Triangles[i]);
      for (int k = 0; k < 3; ++k)
      {
        if (tri[k] != p)
        {
          neighbours.push_back(tri[k]);
        }
      }
    }
    std::sort(neighbours.begin(), neighbours.end());
    int most = 0;
    ForEachRun(neighbours, [&](int triangles) { most = std::max(most, triangles); });
    return most > 2 ? most : 1;
  };
  auto sheetsAt = [&](Id t) {
    if (sheetsOf[t] == 0)
    {
      sheetsOf[t] = 1;
      for (Id i = targetOffsets[t]; i < targetOffsets[t + 1]; ++i)
      {
        sheetsOf[t] = std::max(sheetsOf[t], countSheets(targetPoints[i]));
      }
    }
    return sheetsOf[t];
  };
  std::vector<Id> members, from, to, joined;
  std::vector<Id> around;
  std::vector<std::pair<Id, Id>> directed;
  // Whether `members` of target t, merged into class `root` of `classes`, form one vertex with
  // one fan (or the fan of a curve point where sheets meet, or of a surface without
  // consistent orientation).
  // When the link in from and to (of the vertex merged from `members`) is not one fan: whether
  // it is the fan of a curve point where sheets meet, or one fan of a surface without
  // consistent orientation.
  auto otherFanIsValid = [&](Id t) {
    const int sheets = sheetsAt(t);
    if (sheets > 2)
    {
      return LinkHasShape(from, to, sheets, 2);
    }
    // (The shape first: on a consistent mesh it fails where the directed test did, and the
    // orientation test sorts the whole star.)
    return (LinkHasShape(from, to, 1, 2) || LinkHasShape(from, to, 2, 0)) &&
      HasRepeatedDirectedEdge(triangles, adjacency, members, around, directed);
  };
  auto fanIsValid = [&](std::vector<Id>& classes, Id t, Id root) {
    // (HasOneFan leaves the merged vertex's link edges in from and to.)
    return HasOneFan(triangles, adjacency, classes, members, root, from, to) ||
      otherFanIsValid(t);
  };
  // Whether target t's vertex in the next level (every point merged) passes that test. A
  // level with non-manifold vertices (vertex clustering with PreserveTopology off) has
  // targets that no step can give one fan: they are not held against a step, or every step
  // after the first to reach one could not be stopped at. Asked only when a step fails, and
  // cached; on a manifold level the answer is yes, except where two triangles of this level
  // become the same triangle of the next (which keeps one of them): such a target is let
  // through as well, with the doubled triangle until its transition ends.
  std::vector<Id> merged;                                 // built on the first need
  std::vector<std::uint8_t> nextLevelValid(numberOfTargets, 0); // 0: not asked, 1 yes, 2 no
  auto validInNextLevel = [&](Id t) {
    if (nextLevelValid[t] == 0)
    {
      if (merged.empty())
      {
        merged.resize(numberOfPoints);
        for (Id p = 0; p < numberOfPoints; ++p)
        {
          merged[p] = targetPoints[targetOffsets[target[p]]];
        }
      }
      members.assign(targetPoints.begin() + targetOffsets[t],
        targetPoints.begin() + targetOffsets[t + 1]);
      nextLevelValid[t] = fanIsValid(merged, t, targetPoints[targetOffsets[t]]) ? 1 : 2;
    }
    return nextLevelValid[t] == 1;
  };
  // The link of the target whose collapse is being settled (`tracked`), kept by `link` (see
  // MergedLink): the link edge triangle `tri` gives the vertex of class `root`, if any.
  MergedLink link; // sized when first used (most transitions have no large collapse)
  bool linkSized = false;
  Id tracked = Unassigned;
  auto linkEdge = [&](Id tri, Id root, Id& from, Id& to) {
    const Id* v = triangles + 3 * static_cast<size_t>(tri);
    const Id c[3] = { Find(parent, v[0]), Find(parent, v[1]), Find(parent, v[2]) };
    if (c[0] == c[1] || c[1] == c[2] || c[2] == c[0])
    {
      return false;
    }
    const int k = c[0] == root ? 0 : (c[1] == root ? 1 : (c[2] == root ? 2 : -1));
    if (k < 0)
    {
      return false;
    }
    from = c[(k + 1) % 3];
    to = c[(k + 2) % 3];
    return true;
  };
  // Track target t: its link listed from its settled points.
  auto track = [&](Id t) {
    if (!linkSized)
    {
      link.Reset(numberOfPoints, numberOfTriangles);
      linkSized = true;
    }
    link.Clear();
    tracked = t;
    if (settledOn[t] == Unassigned)
    {
      return;
    }
    const Id root = Find(parent, settledOn[t]);
    for (Id i = targetOffsets[t]; i < targetOffsets[t + 1]; ++i)
    {
      const Id q = targetPoints[i];
      for (Id j = adjacency.Begin(q); j < adjacency.End(q) && this->Step[q] != Unassigned; ++j)
      {
        const Id tri = adjacency.Triangles[j];
        Id from, to;
        if (!link.Holds(tri) && linkEdge(tri, root, from, to))
        {
          link.Add(tri, from, to);
        }
      }
    }
  };
  // Point q (a class of its own until now; a trial may already point it at `root`) joins class
  // `root` of the tracked target: the link edges of its triangles change (the held ones are
  // removed by triangle, whatever q's class). With `removed`, they are kept there for leave().
  std::vector<std::array<Id, 3>> undo;
  auto join = [&](Id q, Id root, std::vector<std::array<Id, 3>>* removed) {
    for (Id j = adjacency.Begin(q); j < adjacency.End(q); ++j)
    {
      const Id tri = adjacency.Triangles[j];
      if (link.Holds(tri))
      {
        const std::pair<Id, Id> e = link.Remove(tri);
        if (removed)
        {
          removed->push_back({ tri, e.first, e.second });
        }
      }
    }
    parent[q] = root;
    for (Id j = adjacency.Begin(q); j < adjacency.End(q); ++j)
    {
      // (A triangle listed twice around q has q twice: degenerate, it gives no edge.)
      const Id tri = adjacency.Triangles[j];
      Id from, to;
      if (!link.Holds(tri) && linkEdge(tri, root, from, to))
      {
        link.Add(tri, from, to);
      }
    }
  };
  // Undoes join(q, ..., &removed): q is a class of its own again (an unsettled point always is,
  // and no other point's parent is it).
  auto leave = [&](Id q, const std::vector<std::array<Id, 3>>& removed) {
    for (Id j = adjacency.Begin(q); j < adjacency.End(q); ++j)
    {
      const Id tri = adjacency.Triangles[j];
      if (link.Holds(tri))
      {
        link.Remove(tri);
      }
    }
    parent[q] = q;
    for (const auto& e : removed)
    {
      link.Add(e[0], e[1], e[2]);
    }
  };
  // Per target, whether two of the triangles around its points use the same directed edge (0:
  // not asked yet, 1: no, 2: yes). Asked when a fan test fails; where no such edge is, the test
  // for a surface without consistent orientation cannot pass for any of its points.
  std::vector<std::uint8_t> inconsistentAt(numberOfTargets, 0);
  auto mayBeInconsistent = [&](Id t) {
    if (inconsistentAt[t] == 0)
    {
      std::vector<Id> all(
        targetPoints.begin() + targetOffsets[t], targetPoints.begin() + targetOffsets[t + 1]);
      inconsistentAt[t] = HasRepeatedDirectedEdge(triangles, adjacency, all, around, directed) ? 2 : 1;
    }
    return inconsistentAt[t] == 2;
  };
  // The points settled on target t, and `extra` (when given), into `members`.
  auto listMembers = [&](Id t, Id extra) {
    members.clear();
    for (Id i = targetOffsets[t]; i < targetOffsets[t + 1]; ++i)
    {
      const Id q = targetPoints[i];
      if (q == extra || this->Step[q] != Unassigned)
      {
        members.push_back(q);
      }
    }
  };
  // fanIsValid for the tracked target t, whose link holds the points settled and `extra`.
  auto trackedFanIsValid = [&](Id t, Id extra) {
    if (link.IsOneFan())
    {
      return true;
    }
    if (sheetsAt(t) <= 2 && !mayBeInconsistent(t))
    {
      return false;
    }
    link.Export(from, to);
    listMembers(t, extra);
    return otherFanIsValid(t);
  };
  // Whether the points settled on target t (and `extra`, when given) form one vertex with one
  // fan; `extra` must already point at the class root.
  auto hasOneFan = [&](Id t, Id extra) {
    if (t == tracked)
    {
      bool valid = false;
      if (extra == Unassigned)
      {
        valid = trackedFanIsValid(t, extra);
      }
      else
      {
        undo.clear();
        join(extra, Find(parent, settledOn[t]), &undo);
        valid = trackedFanIsValid(t, extra);
        leave(extra, undo);
      }
      return valid || !validInNextLevel(t);
    }
    listMembers(t, extra);
    return fanIsValid(parent, t, Find(parent, settledOn[t])) || !validInNextLevel(t);
  };
  // Whether settling p now leaves a valid mesh (p's target keeps one fan).
  auto validWith = [&](Id p) {
    const Id t = target[p];
    if (settledOn[t] == Unassigned)
    {
      return true; // the first point of its target only moves
    }
    const Id saved = parent[p];
    parent[p] = Find(parent, settledOn[t]);
    const bool valid = hasOneFan(t, p);
    parent[p] = saved;
    return valid;
  };
  // Whether the points settled on target t so far form one vertex with one fan.
  auto settledHaveOneFan = [&](Id t) { return hasOneFan(t, Unassigned); };
  // Targets that a step passed through left without one fan. A later step may stop only once
  // none is left: a step's own check sees its target only, and an earlier step's broken
  // target can stay broken (a non-manifold edge, a doubled triangle) while later steps
  // elsewhere pass theirs.
  std::vector<Id> broken;
  std::vector<Id> near; // the targets of the settled points next to a point that settles
  std::vector<std::uint8_t> valid(1, 1);

  // Geometry, when given: a point is at its own position until it settles, then at its
  // target's. The points of a collapse settling one at a time can fold the triangles around the
  // first ones over (an exact-count sphere had triangles facing inwards) or lay three corners
  // on a line (on a flat grid's border). A live triangle that faces neither the way it does in
  // level i nor the way it does once every point has settled (or has no area) is folded; the
  // join order takes points whose join folds nothing around them where it can. (Triangles
  // without area in level i itself, kept from the input, are not judged. Refusing to stop at
  // every step that leaves a fold anywhere made most counts of a collapse of many points
  // unreachable.)
  const bool geometry = positions != nullptr && targetPositions != nullptr;
  waitForFolds = waitForFolds && geometry;
  // Whether triangle tri is live and folded with the settled points, and `extra`, settled.
  auto isFolded = [&](Id tri, Id extra) {
    const Id* v = triangles + 3 * static_cast<size_t>(tri);
    const auto settledNow = [&](Id q) { return q == extra || this->Step[q] != Unassigned; };
    for (int k = 0; k < 3; ++k)
    {
      const Id x = v[k], y = v[(k + 1) % 3];
      if (target[x] == target[y] && settledNow(x) && settledNow(y))
      {
        return false; // gone
      }
    }
    const auto at = [&](int k, bool settled) {
      return (settled ? targetPositions : positions) + 3 * static_cast<size_t>(v[k]);
    };
    double now[3], before[3], after[3];
    Normal(at(0, settledNow(v[0])), at(1, settledNow(v[1])), at(2, settledNow(v[2])), now);
    Normal(at(0, false), at(1, false), at(2, false), before);
    Normal(at(0, true), at(1, true), at(2, true), after);
    const auto faces = [&](const double* m) {
      const double mm = Dot(m, m);
      return mm > 0.0 && Dot(now, m) > FacingTolerance * mm;
    };
    return Dot(before, before) > 0.0 && !faces(before) && !faces(after);
  };
  // Whether settling p now leaves a folded triangle around it.
  auto foldsAround = [&](Id p) {
    for (Id i = adjacency.Begin(p); geometry && i < adjacency.End(p); ++i)
    {
      if (isFolded(adjacency.Triangles[i], p))
      {
        return true;
      }
    }
    return false;
  };

  // The collapses: moving[begin, end) share their rank and target.
  std::vector<std::pair<size_t, size_t>> collapses;
  for (size_t begin = 0; begin < moving.size();)
  {
    const Id first = moving[begin];
    size_t end = begin + 1;
    while (end < moving.size() && target[moving[end]] == target[first] &&
      (rank[moving[end]] < 0) == (rank[first] < 0) &&
      (rank[first] < 0 || rank[moving[end]] == rank[first]))
    {
      ++end;
    }
    collapses.emplace_back(begin, end);
    begin = end;
  }

  // Point p of target t settles as the next step; `ok`: the mesh after it is valid at t.
  auto record = [&](Id p, Id t, bool ok) {
    this->Order.push_back(p);
    this->Step[p] = static_cast<Id>(this->Order.size());
    if (settledOn[t] == Unassigned)
    {
      settledOn[t] = p;
      if (t == tracked)
      {
        track(t);
      }
    }
    else if (t == tracked)
    {
      join(p, Find(parent, settledOn[t]), nullptr);
    }
    parent[Find(parent, p)] = Find(parent, settledOn[t]);
    if (!ok && std::find(broken.begin(), broken.end(), t) == broken.end())
    {
      broken.push_back(t);
    }
    // The broken targets (this one included, when it was broken before) may have one fan
    // again now: t, and those with a point settled next to p. (Another target's vertex keeps
    // its link: only triangles with p as a corner change, and those with a corner settled on
    // it are next to p. Testing every broken target again after every step cost a single
    // level of 158,400 -> 1,584 triangles 3.4 of its 3.8 s.)
    near.clear();
    for (Id j = adjacency.Begin(p); j < adjacency.End(p) && !broken.empty(); ++j)
    {
      const Id* tri = triangles + 3 * static_cast<size_t>(adjacency.Triangles[j]);
      for (int k = 0; k < 3; ++k)
      {
        if (this->Step[tri[k]] != Unassigned)
        {
          near.push_back(target[tri[k]]);
        }
      }
    }
    broken.erase(std::remove_if(broken.begin(), broken.end(),
                   [&](Id b) {
                     const bool changed =
                       b == t || std::find(near.begin(), near.end(), b) != near.end();
                     return changed && (b != t || ok) && settledHaveOneFan(b);
                   }),
      broken.end());
    valid.push_back(ok && broken.empty() ? 1 : 0);
  };

  // Settle a collapse's points one by one, each time among the points joined by an edge to the
  // settled ones (all the collapse's points left, when none is), in increasing id: the first
  // whose merge keeps a valid mesh and folds no triangle around it; else the first whose merge
  // keeps a valid mesh; else the first anyway (the step is then passed through, not stopped
  // at). `wholeValid`: the whole merge was found valid, so the last point needs no test.
  // Those joined points, the frontier, are kept sorted as points settle: a point settling
  // joins its neighbours in the collapse, and nothing else does.
  std::vector<size_t> collapseOfPoint(numberOfPoints, collapses.size());
  for (size_t c = 0; c < collapses.size(); ++c)
  {
    for (size_t i = collapses[c].first; i < collapses[c].second; ++i)
    {
      collapseOfPoint[moving[i]] = c;
    }
  }
  // Whether point q has a neighbour settled on target t.
  const auto nextToSettled = [&](Id q, Id t) {
    for (Id j = adjacency.Begin(q); j < adjacency.End(q); ++j)
    {
      const Id* tri = triangles + 3 * static_cast<size_t>(adjacency.Triangles[j]);
      for (int k = 0; k < 3; ++k)
      {
        if (tri[k] != q && target[tri[k]] == t && this->Step[tri[k]] != Unassigned)
        {
          return true;
        }
      }
    }
    return false;
  };
  SortedIds frontier;
  frontier.In.assign(numberOfPoints, 0);
  auto settle = [&](size_t c, bool wholeValid) {
    const size_t begin = collapses[c].first, end = collapses[c].second;
    const Id t = target[moving[begin]];
    const bool large = end - begin >= std::max<size_t>(1, this->TrackedCollapsePoints);
    if (large)
    {
      track(t);
    }
    // The collapse's points not settled yet, in increasing id.
    const auto listLeft = [&]() {
      joined.clear();
      for (size_t i = begin; i < end; ++i)
      {
        if (this->Step[moving[i]] == Unassigned)
        {
          joined.push_back(moving[i]);
        }
      }
    };
    // The frontier listed from scratch: for a large collapse once, then kept up to date.
    const auto listFrontier = [&]() {
      frontier.Clear();
      for (size_t i = begin; i < end; ++i)
      {
        const Id q = moving[i]; // increasing id: a collapse's points are sorted by id
        if (this->Step[q] == Unassigned && nextToSettled(q, t))
        {
          frontier.Add(q); // (at the end: the ids come in increasing order)
        }
      }
    };
    for (size_t settled = begin; settled < end; ++settled)
    {
      if (settled == begin || !large)
      {
        listFrontier();
      }
      if (wholeValid && settled + 1 == end)
      {
        listLeft();
        record(joined.front(), t, true);
        break;
      }
      // None joined to a settled one (the target's first point, among others): any may go.
      const std::vector<Id>* choices = &frontier.Items;
      if (frontier.Items.empty())
      {
        listLeft();
        choices = &joined;
      }
      // Each test reads the whole merged vertex, so trying every joined point of every step
      // cost a collapse of m points about m^3 (a sphere with points crowded at a pole had one
      // of 6,971 points: 97 s). At most TestBudget / m joined points are tried per step: the
      // first valid merge that folds nothing, else the first valid merge, else the first point.
      // The fold test reads q's own triangles, the fan test the merged vertex's link: the fold
      // test goes first, and the fan test of the first valid point is made only when none of
      // them passes both (where merged points drag long triangles across, most tries fold; a
      // UV sphere's octree levels spent 13 s on fan tests of points that folded).
      const size_t tries =
        std::min(choices->size(), std::max<size_t>(1, TestBudget / (end - begin)));
      Id p = Unassigned;
      for (size_t i = 0; i < tries && p == Unassigned; ++i)
      {
        const Id q = (*choices)[i];
        p = !foldsAround(q) && validWith(q) ? q : Unassigned;
      }
      for (size_t i = 0; i < tries && p == Unassigned; ++i)
      {
        p = validWith((*choices)[i]) ? (*choices)[i] : Unassigned;
      }
      const bool ok = p != Unassigned;
      p = ok ? p : choices->front();
      record(p, t, ok);
      if (!large)
      {
        continue;
      }
      frontier.Remove(p);
      for (Id j = adjacency.Begin(p); j < adjacency.End(p); ++j)
      {
        const Id* tri = triangles + 3 * static_cast<size_t>(adjacency.Triangles[j]);
        for (int k = 0; k < 3; ++k)
        {
          const Id q = tri[k];
          if (collapseOfPoint[q] == c && this->Step[q] == Unassigned)
          {
            frontier.Add(q);
          }
        }
      }
    }
    frontier.Clear();
    link.Clear();
    tracked = Unassigned;
  };

  // Whether collapse c, made whole now, would leave its target with one fan: its points merged
  // for the test and put back (unsettled points are their own roots, so the union-find is
  // restored by resetting them).
  auto wholeIsValid = [&](size_t c) {
    const Id t = target[moving[collapses[c].first]];
    const Id savedOn = settledOn[t];
    if (settledOn[t] == Unassigned)
    {
      settledOn[t] = moving[collapses[c].first];
    }
    const Id root = Find(parent, settledOn[t]);
    for (size_t i = collapses[c].first; i < collapses[c].second; ++i)
    {
      this->Step[moving[i]] = Never; // settled, for the test
      parent[moving[i]] = root;
    }
    bool whole = settledHaveOneFan(t);
    for (size_t i = collapses[c].first; i < collapses[c].second && whole && waitForFolds; ++i)
    {
      whole = !foldsAround(moving[i]);
      this->WaitedForFolds = this->WaitedForFolds || !whole;
    }
    for (size_t i = collapses[c].first; i < collapses[c].second; ++i)
    {
      this->Step[moving[i]] = Unassigned;
      parent[moving[i]] = moving[i];
    }
    settledOn[t] = savedOn;
    return whole;
  };

  // The collapses in order; one whose whole merge would leave its target without one fan waits
  // for a neighbour's merge (see the header). After each collapse made, the waiting ones next
  // to it are tried again.
  std::vector<std::uint8_t> waiting(collapses.size(), 0);
  std::vector<size_t> waitingOfTarget(numberOfTargets, collapses.size());
  std::vector<size_t> triedAfter(collapses.size(), collapses.size()); // at most once per made
  std::vector<size_t> retry;
  size_t waitingNow = 0; // counted until the end, where what waits is made (below)
  for (size_t c = 0; c < collapses.size(); ++c)
  {
    const Id t = target[moving[collapses[c].first]];
    if (waitingOfTarget[t] < collapses.size() || !wholeIsValid(c))
    {
      // (A second collapse of a target that waits waits until the end.)
      waiting[c] = 1;
      waitingOfTarget[t] = std::min(waitingOfTarget[t], c);
      ++waitingNow;
      continue;
    }
    retry.assign(1, c);
    while (!retry.empty())
    {
      const size_t made = retry.back();
      retry.pop_back();
      settle(made, true);
      // Waiting collapses whose target has a point next to this collapse's points (none to
      // look for, the usual case, when nothing waits).
      for (size_t i = collapses[made].first; i < collapses[made].second && waitingNow > 0; ++i)
      {
        const Id q = moving[i];
        for (Id j = adjacency.Begin(q); j < adjacency.End(q); ++j)
        {
          const Id* tri = triangles + 3 * static_cast<size_t>(adjacency.Triangles[j]);
          for (int k = 0; k < 3; ++k)
          {
            const size_t w = waitingOfTarget[target[tri[k]]];
            if (w >= collapses.size() || !waiting[w] || triedAfter[w] == made)
            {
              continue;
            }
            triedAfter[w] = made;
            if (wholeIsValid(w))
            {
              waiting[w] = 0;
              --waitingNow;
              waitingOfTarget[target[tri[k]]] = collapses.size();
              retry.push_back(w);
            }
          }
        }
      }
    }
  }
  // Those still waiting at the end need each other (each valid only once the other is made).
  // They are made by groups of neighbours, one group after the other, each in the order its
  // members are reached from its first: once a group is whole, its targets are as in the next
  // level, so the steps between groups can be stopped at (made in plain order, one broken
  // target kept every later step unstoppable: an extruded text's 19,820-triangle level was the
  // only count below 31,579).
  std::vector<size_t> group;
  std::vector<Id> groupPoints;
  SortedIds candidates;       // indices into groupPoints
  std::vector<Id> groupIndex; // per point: its index in groupPoints, or -1
  std::vector<std::uint8_t> starterSeen;
  if (waitingNow > 0)
  {
    groupIndex.assign(numberOfPoints, -1);
    starterSeen.assign(numberOfTargets, 0);
  }
  for (size_t c = 0; c < collapses.size(); ++c)
  {
    if (!waiting[c])
    {
      continue;
    }
    waiting[c] = 0;
    group.assign(1, c);
    for (size_t g = 0; g < group.size(); ++g)
    {
      const size_t made = group[g];
      for (size_t i = collapses[made].first; i < collapses[made].second; ++i)
      {
        const Id q = moving[i];
        for (Id j = adjacency.Begin(q); j < adjacency.End(q); ++j)
        {
          const Id* tri = triangles + 3 * static_cast<size_t>(adjacency.Triangles[j]);
          for (int k = 0; k < 3; ++k)
          {
            const size_t w = collapseOfPoint[tri[k]];
            if (w < collapses.size() && waiting[w])
            {
              waiting[w] = 0;
              group.push_back(w);
            }
          }
        }
      }
    }
    size_t groupSize = 0, largest = 0;
    for (const size_t made : group)
    {
      groupSize += collapses[made].second - collapses[made].first;
      largest = std::max(largest, collapses[made].second - collapses[made].first);
    }
    if (groupSize > InterleavedGroupPoints)
    {
      for (const size_t made : group)
      {
        settle(made, false);
      }
      continue;
    }
    // The group's points join their targets interleaved. The candidates, in the group's
    // order: the points next to a point settled on their target, and the first point of each
    // target with none settled. Each step takes the first candidate whose join leaves its
    // target with one fan, one of a broken target first, one that folds nothing around it
    // first; else the first candidate.
    groupPoints.clear();
    for (const size_t made : group)
    {
      for (size_t i = collapses[made].first; i < collapses[made].second; ++i)
      {
        groupIndex[moving[i]] = static_cast<Id>(groupPoints.size());
        groupPoints.push_back(moving[i]);
      }
    }
    candidates.Items.clear();
    candidates.In.assign(groupPoints.size(), 0);
    const auto candidate = [&](Id q) {
      if (groupIndex[q] >= 0 && this->Step[q] == Unassigned)
      {
        candidates.Add(groupIndex[q]);
      }
    };
    for (const Id q : groupPoints)
    {
      const Id t = target[q];
      if (settledOn[t] == Unassigned ? !starterSeen[t] : nextToSettled(q, t))
      {
        starterSeen[t] = 1;
        candidate(q);
      }
    }
    for (size_t left = groupPoints.size(); left > 0; --left)
    {
      Id best = Unassigned;
      // 1 + 2 when it fixes a broken target, + 1 when it folds nothing around it; 0: its
      // target is left without one fan.
      int bestClass = 0;
      const int topClass = broken.empty() ? 2 : 4;
      size_t tests = std::max<size_t>(1, TestBudget / largest);
      for (size_t c = 0; c < candidates.Items.size() && tests > 0 && bestClass < topClass;
           ++c, --tests)
      {
        const Id q = groupPoints[static_cast<size_t>(candidates.Items[c])];
        const bool fixes = std::find(broken.begin(), broken.end(), target[q]) != broken.end();
        const int least = 1 + (fixes ? 2 : 0); // its class if valid, folding or not
        if (least + 1 <= bestClass || !validWith(q))
        {
          continue;
        }
        const int cls = least + (foldsAround(q) ? 0 : 1);
        if (cls > bestClass)
        {
          best = q;
          bestClass = cls;
        }
      }
      Id p = best;
      if (p == Unassigned)
      {
        p = candidates.Items.empty() ? Unassigned
                                     : groupPoints[static_cast<size_t>(candidates.Items.front())];
        for (size_t i = 0; p == Unassigned && i < groupPoints.size(); ++i)
        {
          p = this->Step[groupPoints[i]] == Unassigned ? groupPoints[i] : Unassigned;
        }
      }
      record(p, target[p], best != Unassigned);
      candidates.Remove(groupIndex[p]);
      for (Id j = adjacency.Begin(p); j < adjacency.End(p); ++j)
      {
        const Id* tri = triangles + 3 * static_cast<size_t>(adjacency.Triangles[j]);
        for (int k = 0; k < 3; ++k)
        {
          if (target[tri[k]] == target[p])
          {
            candidate(tri[k]);
          }
        }
      }
    }
    for (const Id q : groupPoints)
    {
      groupIndex[q] = -1;
      starterSeen[target[q]] = 0;
    }
  }
  this->Stops.clear();
  for (size_t step = 0; step < valid.size(); ++step)
  {
    if (valid[step])
    {
      this->Stops.push_back(static_cast<Id>(step));
    }
  }

  // A triangle disappears when the second of two corners with the same target settles.
  this->RemovalStep.resize(numberOfTriangles);
  vtkSMPTools::For(0, numberOfTriangles, [&](Id b, Id e) {
    for (Id tri = b; tri < e; ++tri)
    {
      const Id* v = triangles + 3 * static_cast<size_t>(tri);
      Id removal = Never;
      for (int k = 0; k < 3; ++k)
      {
        const Id x = v[k], y = v[(k + 1) % 3];
        if (target[x] == target[y])
        {
          removal = std::min(removal, std::max(this->Step[x], this->Step[y]));
        }
      }
      this->RemovalStep[tri] = removal;
    }
  });

  const Id steps = this->NumberOfSteps();
  this->CountAfter.assign(static_cast<size_t>(steps) + 1, 0);
  for (Id tri = 0; tri < numberOfTriangles; ++tri)
  {
    if (this->RemovalStep[tri] != Never)
    {
      ++this->CountAfter[this->RemovalStep[tri]];
    }
  }
  // Removed by step k -> left after step k.
  Id removed = 0;
  for (Id k = 0; k <= steps; ++k)
  {
    removed += this->CountAfter[k];
    this->CountAfter[k] = numberOfTriangles - removed;
  }
}

//------------------------------------------------------------------------------
Id CollapseSchedule::NumberOfReachableCounts() const
{
  Id counts = 0;
  for (size_t i = 0; i < this->Stops.size(); ++i)
  {
    counts += i == 0 || this->CountAfter[this->Stops[i]] != this->CountAfter[this->Stops[i - 1]];
  }
  return counts;
}

//------------------------------------------------------------------------------
Id CollapseSchedule::StepsForCount(std::int64_t count) const
{
  // Counts only decrease along the steps, so they do along the stops too.
  const auto it = std::partition_point(this->Stops.begin(), this->Stops.end(),
    [&](Id step) { return this->CountAfter[step] > count; });
  return it == this->Stops.end() ? -1 : *it;
}

//------------------------------------------------------------------------------
Id CollapseSchedule::NextRemovingStep(Id steps) const
{
  const Id now = this->CountAfter[steps];
  const auto it = std::partition_point(this->Stops.begin(), this->Stops.end(),
    [&](Id step) { return step <= steps || this->CountAfter[step] == now; });
  return it == this->Stops.end() ? -1 : *it;
}

} // namespace meshlod
