// MeshLOD core: the link of a vertex that points merge into, one at a time (CollapseSchedule).
//
// The link of a merged vertex is the edge (u, w) opposite it in each triangle with exactly one
// corner in it (its two other corners in two other classes), u -> w in the triangle's winding.
// It is one fan when every link vertex with an edge leaving has exactly one and at most one
// entering, there is one path start (a vertex with an edge leaving and none entering) or none
// (a cycle of at least three edges), and the walk from it takes every edge. When a point joins
// the vertex, only the link edges of its own triangles change (no other triangle has a corner
// whose class changes), so a step costs its point's triangles plus a walk along the link (the
// merged vertex's rim, about the square root of the points merged). Listing the link again
// from every merged point at each step made a collapse of m points cost about m^2 (a UV
// sphere's octree levels: 44 s for 636,800 -> 540 triangles).
//
// Each triangle holds at most one link edge, stored densely with its slot per triangle; per
// link vertex, the counts of edges leaving and entering it and the sum of the ends of those
// leaving (the end itself when there is one, which the walk follows). The conditions are
// counted as edges come and go: vertices whose counts break the rule, and path starts (with
// the sum of their ids: the start itself when there is one).
#ifndef meshlod_MergedLink_h
#define meshlod_MergedLink_h

#include "TriangleMesh.h"

#include <cstdint>
#include <utility>
#include <vector>

namespace meshlod
{
class MergedLink
{
public:
  /// Room for link vertices [0, numberOfPoints) and triangles [0, numberOfTriangles); no edge.
  void Reset(Id numberOfPoints, Id numberOfTriangles)
  {
    this->Leaving.assign(numberOfPoints, 0);
    this->Entering.assign(numberOfPoints, 0);
    this->LeavingTo.assign(numberOfPoints, 0);
    this->Slot.assign(numberOfTriangles, -1);
    this->Edges.clear();
    this->Breaking = this->Starts = 0;
    this->StartSum = 0;
  }

  /// Forget every edge (in the time of the edges held).
  void Clear()
  {
    while (!this->Edges.empty())
    {
      this->Remove(this->Edges.back().Triangle);
    }
  }

  /// Whether `triangle` holds a link edge.
  bool Holds(Id triangle) const { return this->Slot[triangle] >= 0; }

  /// The link edge from -> to of `triangle` (which holds none yet).
  void Add(Id triangle, Id from, Id to)
  {
    this->Slot[triangle] = static_cast<Id>(this->Edges.size());
    this->Edges.push_back({ from, to, triangle });
    this->Count(from, to, 1);
  }

  /// Removes the edge of `triangle` (which must hold one); returns it.
  std::pair<Id, Id> Remove(Id triangle)
  {
    const Id slot = this->Slot[triangle];
    const LinkEdge edge = this->Edges[slot];
    this->Edges[slot] = this->Edges.back();
    this->Slot[this->Edges[slot].Triangle] = slot;
    this->Edges.pop_back();
    this->Slot[triangle] = -1;
    this->Count(edge.From, edge.To, -1);
    return { edge.From, edge.To };
  }

  /// Whether the edges held form one fan (an empty link counts as one).
  bool IsOneFan() const
  {
    const size_t n = this->Edges.size();
    if (this->Breaking > 0)
    {
      return false;
    }
    if (n == 0 || this->Starts > 1 || (this->Starts == 0 && n < 3))
    {
      return n == 0;
    }
    // Every vertex with an edge leaving has exactly one: the walk follows LeavingTo.
    const Id start = this->Starts == 1 ? static_cast<Id>(this->StartSum) : this->Edges[0].From;
    size_t walked = 0;
    Id v = start;
    do
    {
      ++walked;
      v = static_cast<Id>(this->LeavingTo[v]);
    } while (this->Leaving[v] > 0 && v != start && walked <= n);
    return walked == n;
  }

  /// The edges held, in no particular order.
  void Export(std::vector<Id>& from, std::vector<Id>& to) const
  {
    from.clear();
    to.clear();
    for (const LinkEdge& e : this->Edges)
    {
      from.push_back(e.From);
      to.push_back(e.To);
    }
  }

private:
  struct LinkEdge
  {
    Id From, To, Triangle;
  };

  bool Breaks(Id v) const
  {
    return this->Leaving[v] > 0 && (this->Leaving[v] != 1 || this->Entering[v] > 1);
  }
  bool IsStart(Id v) const { return this->Leaving[v] > 0 && this->Entering[v] == 0; }

  // Changes the counts of vertex v by `change` (the counters see v's state before and after).
  template <typename Change>
  void Update(Id v, Change&& change)
  {
    this->Breaking -= this->Breaks(v) ? 1 : 0;
    this->Starts -= this->IsStart(v) ? 1 : 0;
    this->StartSum -= this->IsStart(v) ? v : 0;
    change();
    this->Breaking += this->Breaks(v) ? 1 : 0;
    this->Starts += this->IsStart(v) ? 1 : 0;
    this->StartSum += this->IsStart(v) ? v : 0;
  }

  void Count(Id from, Id to, int delta)
  {
    this->Update(from, [&]() {
      this->Leaving[from] += delta;
      this->LeavingTo[from] += delta * static_cast<std::int64_t>(to);
    });
    this->Update(to, [&]() { this->Entering[to] += delta; });
  }

  std::vector<int> Leaving, Entering;
  std::vector<std::int64_t> LeavingTo;
  std::vector<Id> Slot; // per triangle, its edge's index in Edges, or -1
  std::vector<LinkEdge> Edges;
  Id Breaking = 0, Starts = 0;
  std::int64_t StartSum = 0;
};

} // namespace meshlod

#endif
