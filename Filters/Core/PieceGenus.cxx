#include "PieceGenus.h"

#include <algorithm>
#include <numeric>

namespace meshlod
{
namespace
{
void Join(std::vector<Id>& up, Id a, Id b)
{
  a = FindRoot(up, a);
  b = FindRoot(up, b);
  up[std::max(a, b)] = std::min(a, b);
}
} // namespace

std::vector<PieceMeasure> HandleMeasures(const Id* triangles,
  Id count,
  const std::vector<Id>& pointGroup,
  Id groups,
  std::vector<unsigned char>* sideFlags)
{
  const Id points = static_cast<Id>(pointGroup.size());
  const Id corners = 3 * count;
  auto nextCorner = [](Id k) { return k % 3 == 2 ? k - 2 : k + 1; };
  // Each side of each triangle listed at its lower point (as the corner it starts from), in
  // compressed rows sorted by the side's higher point: an edge is then a run of sides with one
  // higher point, as long as its number of triangles.
  auto lower = [&](Id k) { return std::min(triangles[k], triangles[nextCorner(k)]); };
  auto higher = [&](Id k) { return std::max(triangles[k], triangles[nextCorner(k)]); };
  std::vector<Id> offsets(points + 1, 0);
  for (Id k = 0; k < corners; ++k)
  {
    ++offsets[lower(k) + 1];
  }
  std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
  std::vector<Id> sides(corners);
  {
    std::vector<Id> fill(offsets.begin(), offsets.end() - 1);
    for (Id k = 0; k < corners; ++k)
    {
      sides[fill[lower(k)]++] = k;
    }
  }
  for (Id p = 0; p < points; ++p)
  {
    std::sort(sides.begin() + offsets[p], sides.begin() + offsets[p + 1],
      [&](Id a, Id b) { return higher(a) < higher(b) || (higher(a) == higher(b) && a < b); });
  }

  // Points are counted as their fans (corners joined across the edges of two triangles), so
  // that a pinched point (two fans) counts as the two points of the surface it joins: the
  // measure is the surface's, wherever it touches itself.
  std::vector<Id> e(groups, 0), f(groups, 0), v(groups, 0), loops(groups, 0);
  std::vector<unsigned char> nonManifold(groups, 0);
  std::vector<Id> up(corners);
  std::iota(up.begin(), up.end(), Id(0));
  // The pieces: triangles joined across edges of two triangles.
  std::vector<Id> piece(count);
  std::iota(piece.begin(), piece.end(), Id(0));
  // visit(p, first, last) for each edge from p to a higher point: the sides on it.
  auto forEachEdge = [&](auto&& visit)
  {
    for (Id p = 0; p < points; ++p)
    {
      const auto last = sides.begin() + offsets[p + 1];
      for (auto run = sides.begin() + offsets[p]; run != last;)
      {
        const Id q = higher(*run);
        const auto end = std::find_if(run, last, [&](Id k) { return higher(k) != q; });
        visit(p, run, end);
        run = end;
      }
    }
  };
  forEachEdge(
    [&](Id p, auto run, auto end)
    {
      e[pointGroup[p]] += 1;
      if (end - run == 2)
      {
        // (The two sides run in opposite directions where the triangles agree on their
        // orientation, in the same direction where they do not.)
        auto at = [&](Id k, bool atP) { return (triangles[k] == p) == atP ? k : nextCorner(k); };
        Join(up, at(run[0], true), at(run[1], true));
        Join(up, at(run[0], false), at(run[1], false));
        Join(piece, run[0] / 3, run[1] / 3);
      }
      else if (end - run > 2)
      {
        nonManifold[pointGroup[p]] = 1;
      }
    });
  for (Id k = 0; k < corners; ++k)
  {
    v[pointGroup[triangles[k]]] += FindRoot(up, k) == k ? 1 : 0;
  }
  std::vector<Id> pieces(groups, 0);
  for (Id t = 0; t < count; ++t)
  {
    f[pointGroup[triangles[3 * t]]] += 1;
    pieces[pointGroup[triangles[3 * t]]] += FindRoot(piece, t) == t ? 1 : 0;
  }

  // Boundary loops: the fans joined along the sides without another triangle.
  if (sideFlags)
  {
    sideFlags->assign(count, 0);
  }
  std::vector<unsigned char> onBoundary(corners, 0);
  forEachEdge(
    [&](Id, auto run, auto end)
    {
      for (auto side = run; side != end && end - run != 2; ++side)
      {
        const Id k = *side;
        if (end - run == 1)
        {
          onBoundary[k] = onBoundary[nextCorner(k)] = 1;
          Join(up, k, nextCorner(k));
        }
        if (sideFlags)
        {
          (*sideFlags)[k / 3] |= static_cast<unsigned char>(1u << (k % 3 + (end - run == 1 ? 0 : 3)));
        }
      }
    });
  for (Id k = 0; k < corners; ++k)
  {
    const Id root = onBoundary[k] ? FindRoot(up, k) : InvalidId;
    if (root != InvalidId && onBoundary[root] != 2)
    {
      onBoundary[root] = 2; // counted
      loops[pointGroup[triangles[root]]] += 1;
    }
  }

  std::vector<PieceMeasure> measures(groups);
  for (Id g = 0; g < groups; ++g)
  {
    if (f[g] > 0 && !nonManifold[g])
    {
      measures[g].Pieces = pieces[g];
      measures[g].Handles = 2 * pieces[g] - v[g] + e[g] - f[g] - loops[g];
      measures[g].Measured = true;
    }
  }
  return measures;
}
} // namespace meshlod
