#include "LevelTracker.h"

#include "LevelData.h"
#include "CollapseMesh.h"

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
  const TriangleMesh& mesh = state.Mesh;
  const Id nv = mesh.GetNumberOfPoints();
  const Id nt = mesh.GetNumberOfTriangles();

  // Live vertices (a live vertex has live triangles) and triangles, numbered in increasing id
  // order.
  std::vector<Id>& newIndex = this->NewIndex; // kept between snapshots: no fresh pages each time
  newIndex.assign(nv, InvalidId);
  std::vector<Id> vertices;
  for (Id v = 0; v < nv; ++v)
  {
    if (state.Survivor[v] == v && state.TriangleCount(v) > 0)
    {
      newIndex[v] = static_cast<Id>(vertices.size());
      vertices.push_back(v);
    }
  }
  const Id count = static_cast<Id>(vertices.size());

  level = LevelData();
  level.EstimatedError = estimatedError;
  level.Mesh.Points.resize(3 * static_cast<std::size_t>(count));
  vtkSMPTools::For(0, count, [&](Id begin, Id end) {
    for (Id i = begin; i < end; ++i)
    {
      std::copy_n(mesh.Point(vertices[i]), 3, level.Mesh.Point(i));
    }
  });
  level.Mesh.Triangles.reserve(3 * static_cast<std::size_t>(state.AliveTriangles));
  level.LevelZeroTriangle.reserve(state.AliveTriangles);
  for (Id t = 0; t < nt; ++t)
  {
    if (state.IsAlive(t))
    {
      const Id* tri = mesh.Triangle(t);
      level.Mesh.Triangles.insert(
        level.Mesh.Triangles.end(), { newIndex[tri[0]], newIndex[tri[1]], newIndex[tri[2]] });
      level.LevelZeroTriangle.push_back(t);
    }
  }

  // Point sources: the previous level's points of each group, with their weights.
  level.Sources.Clear();
  level.Sources.Offsets.reserve(count + 1);
  level.Sources.Parents.reserve(this->PreviousVertices.size());
  level.Sources.Weights.reserve(this->PreviousVertices.size());
  for (const Id v : vertices)
  {
    for (Id u = v; u != InvalidId; u = this->GroupNext[u])
    {
      level.Sources.Parents.push_back(this->PreviousIndex[u]);
      level.Sources.Weights.push_back(this->GroupWeight[u]);
    }
    level.Sources.Offsets.push_back(static_cast<Id>(level.Sources.Parents.size()));
  }

  // Correspondence and collapse order of the previous level's points. Ranks are the order of
  // the last collapse of each group, renumbered 0, 1, 2, ...: sort the groups that collapsed by
  // that collapse, and give every point the rank of the group it ends in.
  std::vector<std::pair<std::int64_t, Id>> order; // (collapse, new point)
  for (Id i = 0; i < count; ++i)
  {
    const std::int64_t sequence = this->GroupSequence[vertices[i]];
    if (sequence >= 0)
    {
      order.emplace_back(sequence, i);
    }
  }
  std::sort(order.begin(), order.end());
  std::vector<Id> rankOf(count, InvalidId);
  for (std::size_t r = 0; r < order.size(); ++r)
  {
    rankOf[order[r].second] = static_cast<Id>(r);
  }
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
  for (Id i = 0; i < count; ++i)
  {
    const Id v = vertices[i];
    this->GroupNext[v] = InvalidId;
    this->GroupTail[v] = v;
    this->GroupWeight[v] = 1.0f;
    this->GroupSequence[v] = -1;
    this->PreviousIndex[v] = i;
  }
  this->PreviousVertices.swap(vertices);
}

} // namespace meshlod
