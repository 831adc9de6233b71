#include "LevelTracker.h"

#include "CollapseMesh.h"
#include "FreshMemory.h"
#include "LevelData.h"
#include "ParallelCompact.h"

#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <limits>
#include <numeric>
#include <utility>

namespace meshlod
{
namespace
{
// Snapshot ranks collapses by a counting sort when their numbers span at most this many times
// their count, plus this many.
constexpr std::int64_t CountingSortSpan = 4;
constexpr std::int64_t CountingSortSlack = 4096;
}

void LevelTracker::Initialize(Id numberOfPoints, bool trackAncestors)
{
  AssignFresh(this->GroupNext, numberOfPoints, InvalidId);
  ResizeFresh(this->GroupTail, numberOfPoints);
  std::iota(this->GroupTail.begin(), this->GroupTail.end(), 0);
  AssignFresh(this->GroupWeight, numberOfPoints, 1.0f);
  AssignFresh(this->GroupSequence, numberOfPoints, -1);
  ResizeFresh(this->PreviousIndex, numberOfPoints);
  std::iota(this->PreviousIndex.begin(), this->PreviousIndex.end(), 0);
  ReserveFresh(this->PreviousVertices, numberOfPoints);
  this->PreviousVertices = this->PreviousIndex;
  this->Ancestors.clear();
  this->AncestorStart.clear();
  this->AncestorTotal.clear();
  if (trackAncestors)
  {
    ReserveFresh(this->Ancestors, numberOfPoints);
    this->Ancestors = this->PreviousIndex;
    ResizeFresh(this->AncestorStart, static_cast<std::size_t>(numberOfPoints) + 1);
    std::iota(this->AncestorStart.begin(), this->AncestorStart.end(), 0);
    AssignFresh(this->AncestorTotal, numberOfPoints, 1);
  }
}

//------------------------------------------------------------------------------
void LevelTracker::Merge(const Id* members, const double* weights, int count, std::int64_t sequence)
{
  const Id survivor = members[0];
  for (int m = 0; m < count; ++m)
  {
    const float w = static_cast<float>(weights[m]);
    for (Id u = members[m]; u != InvalidId; u = this->GroupNext[u])
    {
      this->GroupWeight[u] *= w;
    }
  }
  for (int m = 1; m < count; ++m)
  {
    const Id v = members[m];
    this->GroupNext[this->GroupTail[survivor]] = v;
    this->GroupTail[survivor] = this->GroupTail[v];
    if (!this->AncestorTotal.empty())
    {
      this->AncestorTotal[survivor] += this->AncestorTotal[v];
    }
  }
  this->GroupSequence[survivor] = sequence;
}

//------------------------------------------------------------------------------
void LevelTracker::Snapshot(const CollapseMesh& state, double estimatedError, LevelData& level,
  const std::vector<Id>* triangles)
{
  // Every pass is data-parallel, with the same result for any number of threads (compactions
  // by fixed blocks, a counting sort or a sort of distinct keys): with two threads the serial
  // passes here had been a tenth of the whole hierarchy's time.
  std::vector<Id> vertices = this->ListLiveVertices(state);
  level = LevelData();
  level.EstimatedError = estimatedError;
  this->CopyLiveMesh(state, vertices, triangles, level);
  this->WriteSources(vertices, level.Sources);
  this->WriteCorrespondence(state, this->RankCollapses(vertices), level);
  if (!this->AncestorTotal.empty())
  {
    this->LayOutAncestors(vertices);
  }

  // New groups for the next level.
  const Id count = static_cast<Id>(vertices.size());
  vtkSMPTools::For(0, count, [&](Id begin, Id end) {
    for (Id i = begin; i < end; ++i)
    {
      const Id v = vertices[i];
      this->GroupNext[v] = InvalidId;
      this->GroupTail[v] = v;
      this->GroupWeight[v] = 1.0f;
      this->GroupSequence[v] = -1;
      this->PreviousIndex[v] = i;
    }
  });
  this->PreviousVertices.swap(vertices);
}

//------------------------------------------------------------------------------
// Live vertices (a live vertex has live triangles, or is what is left of a vanished piece),
// numbered in increasing id order, with NewIndex mapping them to their numbers. Only the last
// level's vertices are looked at (nothing comes alive again).
std::vector<Id> LevelTracker::ListLiveVertices(const CollapseMesh& state)
{
  const std::vector<Id>& candidates = this->PreviousVertices;
  const auto liveVertex = [&](Id i) {
    const Id v = candidates[i];
    return state.Survivor[v] == v &&
      (state.TriangleCount(v) > 0 || (state.Flags[v] & FlagVanished) != 0);
  };
  const ParallelCompaction liveVertices(static_cast<Id>(candidates.size()), liveVertex);
  std::vector<Id>& newIndex = this->NewIndex; // kept between snapshots: no fresh pages each time
  ResizeFresh(newIndex, state.Mesh.GetNumberOfPoints());
  vtkSMPTools::Fill(newIndex.begin(), newIndex.end(), InvalidId);
  std::vector<Id> vertices = FreshVector<Id>(liveVertices.Count());
  liveVertices.Write(liveVertex, [&](Id i, Id slot) {
    newIndex[candidates[i]] = slot;
    vertices[slot] = candidates[i];
  });
  return vertices;
}

// The level's points (the live `vertices`) and its live triangles, numbered in increasing id
// order: among `triangles` when given (at the coarse levels a small part of the mesh), else all.
void LevelTracker::CopyLiveMesh(const CollapseMesh& state, const std::vector<Id>& vertices,
  const std::vector<Id>* triangles, LevelData& level) const
{
  const TriangleMesh& mesh = state.Mesh;
  const Id count = static_cast<Id>(vertices.size());
  const std::vector<Id>& newIndex = this->NewIndex;
  ResizeFresh(level.Mesh.Points, 3 * static_cast<std::size_t>(count));
  vtkSMPTools::For(0, count, [&](Id begin, Id end) {
    for (Id i = begin; i < end; ++i)
    {
      std::copy_n(mesh.Point(vertices[i]), 3, level.Mesh.Point(i));
    }
  });
  const bool all = triangles == nullptr;
  const auto triangleAt = [&](Id i) { return all ? i : (*triangles)[i]; };
  const auto liveTriangle = [&](Id i) { return state.IsAlive(triangleAt(i)); };
  const ParallelCompaction liveTriangles(
    all ? mesh.GetNumberOfTriangles() : static_cast<Id>(triangles->size()), liveTriangle);
  ResizeFresh(level.Mesh.Triangles, 3 * static_cast<std::size_t>(liveTriangles.Count()));
  ResizeFresh(level.LevelZeroTriangle, liveTriangles.Count());
  liveTriangles.Write(liveTriangle, [&](Id i, Id slot) {
    const Id t = triangleAt(i);
    const Id* tri = mesh.Triangle(t);
    Id* out = level.Mesh.Triangle(slot);
    out[0] = newIndex[tri[0]];
    out[1] = newIndex[tri[1]];
    out[2] = newIndex[tri[2]];
    level.LevelZeroTriangle[slot] = t;
  });
}

// Point sources: the previous level's points of each group, with their weights.
void LevelTracker::WriteSources(const std::vector<Id>& vertices, PointSources& sources) const
{
  const Id count = static_cast<Id>(vertices.size());
  ResizeFresh(sources.Offsets, static_cast<std::size_t>(count) + 1);
  sources.Offsets[0] = 0;
  vtkSMPTools::For(0, count, [&](Id begin, Id end) {
    for (Id i = begin; i < end; ++i)
    {
      Id members = 0;
      for (Id u = vertices[i]; u != InvalidId; u = this->GroupNext[u])
      {
        ++members;
      }
      sources.Offsets[i + 1] = members;
    }
  });
  for (Id i = 0; i < count; ++i)
  {
    sources.Offsets[i + 1] += sources.Offsets[i];
  }
  ResizeFresh(sources.Parents, sources.Offsets[count]);
  ResizeFresh(sources.Weights, sources.Offsets[count]);
  vtkSMPTools::For(0, count, [&](Id begin, Id end) {
    for (Id i = begin; i < end; ++i)
    {
      Id slot = sources.Offsets[i];
      for (Id u = vertices[i]; u != InvalidId; u = this->GroupNext[u], ++slot)
      {
        sources.Parents[slot] = this->PreviousIndex[u];
        sources.Weights[slot] = this->GroupWeight[u];
      }
    }
  });
}

//------------------------------------------------------------------------------
// Per live vertex, the rank of its group's last collapse: the collapse numbers renumbered 0, 1,
// 2, ... by sorting the groups that collapsed by that collapse (distinct numbers: one
// collapse, one survivor); InvalidId for a group that did not collapse.
std::vector<Id> LevelTracker::RankCollapses(const std::vector<Id>& vertices)
{
  const Id count = static_cast<Id>(vertices.size());
  const auto collapsed = [&](Id i) { return this->GroupSequence[vertices[i]] >= 0; };
  const ParallelCompaction collapsedGroups(count, collapsed);
  std::vector<Id> rankOf = FreshVector<Id>(count, InvalidId);
  // The range of the level's collapse numbers.
  using Range = std::pair<std::int64_t, std::int64_t>;
  vtkSMPThreadLocal<Range> ranges(Range(std::numeric_limits<std::int64_t>::max(), -1));
  vtkSMPTools::For(0, count, [&](Id begin, Id end) {
    Range& range = ranges.Local();
    for (Id i = begin; i < end; ++i)
    {
      const std::int64_t number = this->GroupSequence[vertices[i]];
      if (number >= 0)
      {
        range.first = std::min(range.first, number);
        range.second = std::max(range.second, number);
      }
    }
  });
  Range range(std::numeric_limits<std::int64_t>::max(), -1);
  for (const Range& r : ranges)
  {
    range = Range(std::min(range.first, r.first), std::max(range.second, r.second));
  }
  const std::int64_t span = range.second - range.first + 1;
  if (span > 0 && span <= CountingSortSpan * collapsedGroups.Count() + CountingSortSlack)
  {
    // The numbers lie in a short range (parallel rounds leave gaps in it): a counting sort.
    std::vector<Id>& byCollapse = this->ByCollapse; // collapse number - first -> point
    ResizeFresh(byCollapse, static_cast<std::size_t>(span));
    vtkSMPTools::Fill(byCollapse.begin(), byCollapse.end(), InvalidId);
    const std::int64_t first = range.first;
    collapsedGroups.Write(collapsed, [&](Id i, Id) {
      byCollapse[static_cast<std::size_t>(this->GroupSequence[vertices[i]] - first)] = i;
    });
    const auto used = [&](Id k) { return byCollapse[k] != InvalidId; };
    ParallelCompact(static_cast<Id>(span), used,
      [&](Id k, Id rank) { rankOf[byCollapse[k]] = rank; });
  }
  else
  {
    std::vector<std::pair<std::int64_t, Id>> order(collapsedGroups.Count()); // (collapse, point)
    collapsedGroups.Write(collapsed, [&](Id i, Id slot) {
      order[slot] = { this->GroupSequence[vertices[i]], i };
    });
    vtkSMPTools::Sort(order.begin(), order.end());
    vtkSMPTools::For(0, static_cast<Id>(order.size()), [&](Id begin, Id end) {
      for (Id r = begin; r < end; ++r)
      {
        rankOf[order[r].second] = r;
      }
    });
  }
  return rankOf;
}

// Correspondence and collapse order of the previous level's points: every point takes the
// number and the rank (`rankOf`) of the group it ends in.
void LevelTracker::WriteCorrespondence(
  const CollapseMesh& state, const std::vector<Id>& rankOf, LevelData& level) const
{
  const std::vector<Id>& newIndex = this->NewIndex;
  const Id previousCount = static_cast<Id>(this->PreviousVertices.size());
  ResizeFresh(level.Target, previousCount);
  ResizeFresh(level.Rank, previousCount);
  vtkSMPTools::For(0, previousCount, [&](Id begin, Id end) {
    for (Id k = begin; k < end; ++k)
    {
      Id root = this->PreviousVertices[k];
      while (state.Survivor[root] != root)
      {
        root = state.Survivor[root];
      }
      level.Target[k] = newIndex[root];
      level.Rank[k] = newIndex[root] == InvalidId ? InvalidId : rankOf[newIndex[root]];
    }
  });
}

//------------------------------------------------------------------------------
// One run per vertex of the new level: the runs of its group's vertices, in group order. Needs
// the last level's groups and numbering (before they are reset).
void LevelTracker::LayOutAncestors(const std::vector<Id>& vertices)
{
  const Id count = static_cast<Id>(vertices.size());
  std::vector<Id> start(static_cast<std::size_t>(count) + 1);
  start[0] = 0;
  for (Id i = 0; i < count; ++i)
  {
    start[i + 1] = start[i] + this->AncestorTotal[vertices[i]];
  }
  ResizeFresh(this->NewAncestors, start[count]);
  vtkSMPTools::For(0, count, [&](Id begin, Id end) {
    for (Id i = begin; i < end; ++i)
    {
      Id* out = this->NewAncestors.data() + start[i];
      for (Id u = vertices[i]; u != InvalidId; u = this->GroupNext[u])
      {
        const Id run = this->PreviousIndex[u];
        out = std::copy(this->Ancestors.begin() + this->AncestorStart[run],
          this->Ancestors.begin() + this->AncestorStart[run + 1], out);
      }
    }
  });
  this->Ancestors.swap(this->NewAncestors);
  this->AncestorStart.swap(start);
}

} // namespace meshlod
