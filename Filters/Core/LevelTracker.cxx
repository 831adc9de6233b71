#include "LevelTracker.h"

#include "LevelData.h"
#include "CollapseMesh.h"
#include "ParallelCompact.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <numeric>
#include <utility>

namespace meshlod
{
void LevelTracker::Initialize(Id numberOfPoints, bool trackAncestors)
{
  this->GroupNext.assign(numberOfPoints, InvalidId);
  this->GroupTail.resize(numberOfPoints);
  std::iota(this->GroupTail.begin(), this->GroupTail.end(), 0);
  this->GroupWeight.assign(numberOfPoints, 1.0f);
  this->GroupSequence.assign(numberOfPoints, -1);
  this->PreviousIndex.resize(numberOfPoints);
  std::iota(this->PreviousIndex.begin(), this->PreviousIndex.end(), 0);
  this->PreviousVertices = this->PreviousIndex;
  this->AncestorNext.clear();
  this->AncestorTail.clear();
  this->AncestorTotal.clear();
  if (trackAncestors)
  {
    this->AncestorNext.assign(numberOfPoints, InvalidId);
    this->AncestorTail = this->GroupTail;
    this->AncestorTotal.assign(numberOfPoints, 1);
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
    if (!this->AncestorNext.empty())
    {
      this->AncestorNext[this->AncestorTail[survivor]] = v;
      this->AncestorTail[survivor] = this->AncestorTail[v];
      this->AncestorTotal[survivor] += this->AncestorTotal[v];
    }
  }
  this->GroupSequence[survivor] = sequence;
}

//------------------------------------------------------------------------------
void LevelTracker::Snapshot(const CollapseMesh& state, double estimatedError, LevelData& level)
{
  // Every pass is data-parallel, with the same result for any number of threads (compactions
  // by fixed blocks, a sort of distinct keys): with two threads the serial passes here had
  // been a tenth of the whole hierarchy's time.
  const TriangleMesh& mesh = state.Mesh;
  const Id nv = mesh.GetNumberOfPoints();
  const Id nt = mesh.GetNumberOfTriangles();

  // Live vertices (a live vertex has live triangles) and triangles, numbered in increasing id
  // order.
  const auto liveVertex = [&](Id v) {
    return state.Survivor[v] == v && state.TriangleCount(v) > 0;
  };
  const ParallelCompaction liveVertices(nv, liveVertex);
  const Id count = liveVertices.Count();
  std::vector<Id>& newIndex = this->NewIndex; // kept between snapshots: no fresh pages each time
  newIndex.resize(nv);
  vtkSMPTools::Fill(newIndex.begin(), newIndex.end(), InvalidId);
  std::vector<Id> vertices(count);
  liveVertices.Write(liveVertex, [&](Id v, Id slot) {
    newIndex[v] = slot;
    vertices[slot] = v;
  });

  level = LevelData();
  level.EstimatedError = estimatedError;
  level.Mesh.Points.resize(3 * static_cast<std::size_t>(count));
  vtkSMPTools::For(0, count, [&](Id begin, Id end) {
    for (Id i = begin; i < end; ++i)
    {
      std::copy_n(mesh.Point(vertices[i]), 3, level.Mesh.Point(i));
    }
  });
  const auto liveTriangle = [&](Id t) { return state.IsAlive(t); };
  const ParallelCompaction liveTriangles(nt, liveTriangle);
  level.Mesh.Triangles.resize(3 * static_cast<std::size_t>(liveTriangles.Count()));
  level.LevelZeroTriangle.resize(liveTriangles.Count());
  liveTriangles.Write(liveTriangle, [&](Id t, Id slot) {
    const Id* tri = mesh.Triangle(t);
    Id* out = level.Mesh.Triangle(slot);
    out[0] = newIndex[tri[0]];
    out[1] = newIndex[tri[1]];
    out[2] = newIndex[tri[2]];
    level.LevelZeroTriangle[slot] = t;
  });

  // Point sources: the previous level's points of each group, with their weights.
  PointSources& sources = level.Sources;
  sources.Offsets.resize(static_cast<std::size_t>(count) + 1);
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
  sources.Parents.resize(sources.Offsets[count]);
  sources.Weights.resize(sources.Offsets[count]);
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

  // Correspondence and collapse order of the previous level's points. Ranks are the order of
  // the last collapse of each group, renumbered 0, 1, 2, ...: sort the groups that collapsed by
  // that collapse (distinct numbers: one collapse, one survivor), and give every point the
  // rank of the group it ends in.
  const auto collapsed = [&](Id i) { return this->GroupSequence[vertices[i]] >= 0; };
  const ParallelCompaction collapsedGroups(count, collapsed);
  std::vector<std::pair<std::int64_t, Id>> order(collapsedGroups.Count()); // (collapse, point)
  collapsedGroups.Write(collapsed, [&](Id i, Id slot) {
    order[slot] = { this->GroupSequence[vertices[i]], i };
  });
  vtkSMPTools::Sort(order.begin(), order.end());
  std::vector<Id> rankOf(count, InvalidId);
  vtkSMPTools::For(0, static_cast<Id>(order.size()), [&](Id begin, Id end) {
    for (Id r = begin; r < end; ++r)
    {
      rankOf[order[r].second] = r;
    }
  });
  const Id previousCount = static_cast<Id>(this->PreviousVertices.size());
  level.Target.resize(previousCount);
  level.Rank.resize(previousCount);
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

  // New groups for the next level.
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

} // namespace meshlod
