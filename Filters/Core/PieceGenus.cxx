#include "PieceGenus.h"

#include "ConcurrentForest.h"
#include "FreshMemory.h"

#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cstdint>

namespace meshlod
{
namespace
{
// One group's counts, summed by each thread over the items it is given and added up after
// (integer sums: the same for any split of the work).
struct GroupCounts
{
  Id Edges = 0;
  Id Triangles = 0;
  Id Fans = 0;
  Id Pieces = 0;
  bool NonManifold = false;
};
using ThreadCounts = vtkSMPThreadLocal<std::vector<GroupCounts>>;

// What lies across a triangle's side (one byte per corner: the side from it to the next).
enum SideKind : unsigned char
{
  TwoTriangles = 0,
  Boundary = 1,
  ThreeOrMore = 2
};

// body(begin, end, counts) over [0, n) with vtkSMPTools, counts the running thread's own.
template <typename Body>
void ForEachCounting(Id n, ThreadCounts& counts, Body&& body)
{
  vtkSMPTools::For(0, n, [&](Id begin, Id end) { body(begin, end, counts.Local()); });
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
  // An edge is a run of sides with one higher point in its lower point's row, as long as its
  // number of triangles.
  std::vector<Id> offsets;
  std::vector<std::uint64_t> sides;
  ListSidesByLowerPoint(triangles, count, points, nullptr, offsets, sides);

  ThreadCounts counts(std::vector<GroupCounts>(static_cast<std::size_t>(groups)));
  // Points are counted as their fans (corners joined across the edges of two triangles), so
  // that a pinched point (two fans) counts as the two points of the surface it joins: the
  // measure is the surface's, wherever it touches itself. The pieces: triangles joined across
  // edges of two triangles.
  ConcurrentForest fans(corners);
  ConcurrentForest pieces(count);
  std::vector<unsigned char> kind = FreshVector<unsigned char>(corners, TwoTriangles);
  ForEachCounting(points, counts, [&](Id begin, Id end, std::vector<GroupCounts>& mine) {
    for (Id p = begin; p < end; ++p)
    {
      GroupCounts& group = mine[pointGroup[p]];
      const auto last = sides.begin() + offsets[p + 1];
      for (auto run = sides.begin() + offsets[p]; run != last;)
      {
        const Id q = SideHigherPoint(*run);
        const auto next =
          std::find_if(run, last, [&](std::uint64_t side) { return SideHigherPoint(side) != q; });
        group.Edges += 1;
        if (next - run == 2)
        {
          // (The two sides run in opposite directions where the triangles agree on their
          // orientation, in the same direction where they do not.)
          const Id a = SideCorner(run[0]), b = SideCorner(run[1]);
          auto at = [&](Id k, bool atP) { return (triangles[k] == p) == atP ? k : NextCorner(k); };
          fans.Join(at(a, true), at(b, true));
          fans.Join(at(a, false), at(b, false));
          pieces.Join(a / 3, b / 3);
        }
        else
        {
          group.NonManifold |= next - run > 2;
          for (auto side = run; side != next; ++side)
          {
            kind[SideCorner(*side)] = next - run == 1 ? Boundary : ThreeOrMore;
          }
        }
        run = next;
      }
    }
  });
  ForEachCounting(count, counts, [&](Id begin, Id end, std::vector<GroupCounts>& mine) {
    for (Id t = begin; t < end; ++t)
    {
      GroupCounts& group = mine[pointGroup[triangles[3 * t]]];
      group.Triangles += 1;
      group.Pieces += pieces.IsRoot(t) ? 1 : 0;
      for (Id k = 3 * t; k < 3 * t + 3; ++k)
      {
        mine[pointGroup[triangles[k]]].Fans += fans.IsRoot(k) ? 1 : 0;
      }
    }
  });

  // Boundary loops: the fans joined along the sides without another triangle, each loop
  // counted at its root (its smallest corner) in the group of that corner's point.
  std::vector<Id> loops(static_cast<std::size_t>(groups), 0);
  bool anyBoundary = false;
  for (Id k = 0; k < corners && !anyBoundary; ++k)
  {
    anyBoundary = kind[k] == Boundary;
  }
  if (anyBoundary)
  {
    vtkSMPTools::For(0, corners, [&](Id begin, Id end) {
      for (Id k = begin; k < end; ++k)
      {
        if (kind[k] == Boundary)
        {
          fans.Join(k, NextCorner(k));
        }
      }
    });
    std::vector<unsigned char> counted = FreshVector<unsigned char>(corners, 0);
    for (Id k = 0; k < corners; ++k)
    {
      if (kind[k] == Boundary || kind[PreviousCorner(k)] == Boundary)
      {
        const Id root = fans.Root(k);
        if (!counted[root])
        {
          counted[root] = 1;
          loops[pointGroup[triangles[root]]] += 1;
        }
      }
    }
  }
  if (sideFlags)
  {
    ResizeFresh(*sideFlags, count);
    vtkSMPTools::For(0, count, [&](Id begin, Id end) {
      for (Id t = begin; t < end; ++t)
      {
        unsigned char flags = 0;
        for (int c = 0; c < 3; ++c)
        {
          const unsigned char side = kind[3 * t + c];
          flags |= static_cast<unsigned char>(
            side == Boundary ? 1u << c : side == ThreeOrMore ? 1u << (c + 3) : 0u);
        }
        (*sideFlags)[t] = flags;
      }
    });
  }

  std::vector<GroupCounts> total(static_cast<std::size_t>(groups));
  for (const std::vector<GroupCounts>& mine : counts)
  {
    for (Id g = 0; g < groups; ++g)
    {
      total[g].Edges += mine[g].Edges;
      total[g].Triangles += mine[g].Triangles;
      total[g].Fans += mine[g].Fans;
      total[g].Pieces += mine[g].Pieces;
      total[g].NonManifold |= mine[g].NonManifold;
    }
  }
  std::vector<PieceMeasure> measures(static_cast<std::size_t>(groups));
  for (Id g = 0; g < groups; ++g)
  {
    const GroupCounts& c = total[g];
    if (c.Triangles > 0 && !c.NonManifold)
    {
      measures[g].Pieces = c.Pieces;
      measures[g].Handles = 2 * c.Pieces - c.Fans + c.Edges - c.Triangles - loops[g];
      measures[g].Measured = true;
    }
  }
  return measures;
}
} // namespace meshlod
