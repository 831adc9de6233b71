#include "CollapseSchedule.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <functional>
#include <limits>
#include <queue>

namespace meshlod
{
namespace
{
constexpr Id Unassigned = -1;

// Points of each target, as compressed rows (counting sort, rows in increasing point id).
void GroupByTarget(const Id* target, Id numberOfPoints, Id numberOfTargets,
  std::vector<Id>& offsets, std::vector<Id>& points)
{
  offsets.assign(static_cast<size_t>(numberOfTargets) + 1, 0);
  for (Id p = 0; p < numberOfPoints; ++p)
  {
    ++offsets[target[p] + 1];
  }
  for (Id t = 0; t < numberOfTargets; ++t)
  {
    offsets[t + 1] += offsets[t];
  }
  points.resize(numberOfPoints);
  std::vector<Id> cursor(offsets.begin(), offsets.end() - 1);
  for (Id p = 0; p < numberOfPoints; ++p)
  {
    points[cursor[target[p]]++] = p;
  }
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
} // namespace

//------------------------------------------------------------------------------
void CollapseSchedule::Build(const Id* triangles, Id numberOfTriangles, Id numberOfPoints,
  const Id* target, const std::int64_t* rank, const std::uint8_t* atTarget)
{
  this->Step.assign(numberOfPoints, Unassigned);
  this->Order.clear();
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
  std::vector<Id> targetOffsets, targetPoints;
  GroupByTarget(target, numberOfPoints, numberOfTargets, targetOffsets, targetPoints);
  VertexTriangleAdjacency adjacency;
  adjacency.Build(triangles, numberOfTriangles, numberOfPoints);

  const std::vector<Id> moving = SortMovingPoints(numberOfPoints, target, rank, atTarget);
  this->Order.reserve(moving.size());
  // Which collapse a moving point belongs to (its first index in `moving` + 1).
  std::vector<Id> collapseOf(numberOfPoints, 0);
  std::priority_queue<Id, std::vector<Id>, std::greater<Id>> frontier;
  auto pushNeighbors = [&](Id p, Id collapse) {
    for (Id i = adjacency.Begin(p); i < adjacency.End(p); ++i)
    {
      const Id* tri = triangles + 3 * static_cast<size_t>(adjacency.Triangles[i]);
      for (int k = 0; k < 3; ++k)
      {
        if (collapseOf[tri[k]] == collapse && this->Step[tri[k]] == Unassigned)
        {
          frontier.push(tri[k]);
        }
      }
    }
  };

  size_t begin = 0;
  while (begin < moving.size())
  {
    // One collapse: moving[begin, end) share their rank and target.
    const Id first = moving[begin];
    size_t end = begin + 1;
    while (end < moving.size() && target[moving[end]] == target[first] &&
      (rank[moving[end]] < 0) == (rank[first] < 0) &&
      (rank[first] < 0 || rank[moving[end]] == rank[first]))
    {
      ++end;
    }
    const Id collapse = static_cast<Id>(begin) + 1;
    for (size_t i = begin; i < end; ++i)
    {
      collapseOf[moving[i]] = collapse;
    }
    // Seeds: points already settled on this target.
    const Id t = target[first];
    for (Id i = targetOffsets[t]; i < targetOffsets[t + 1]; ++i)
    {
      if (this->Step[targetPoints[i]] != Unassigned)
      {
        pushNeighbors(targetPoints[i], collapse);
      }
    }
    size_t lowestLeft = begin;
    for (size_t settled = begin; settled < end; ++settled)
    {
      Id p = Unassigned;
      while (!frontier.empty() && p == Unassigned)
      {
        p = this->Step[frontier.top()] == Unassigned ? frontier.top() : Unassigned;
        frontier.pop();
      }
      if (p == Unassigned)
      {
        while (this->Step[moving[lowestLeft]] != Unassigned)
        {
          ++lowestLeft;
        }
        p = moving[lowestLeft];
      }
      this->Order.push_back(p);
      this->Step[p] = static_cast<Id>(this->Order.size());
      pushNeighbors(p, collapse);
    }
    while (!frontier.empty())
    {
      frontier.pop();
    }
    begin = end;
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
Id CollapseSchedule::StepsForCount(std::int64_t count) const
{
  const auto it = std::partition_point(
    this->CountAfter.begin(), this->CountAfter.end(), [count](Id left) { return left > count; });
  return it == this->CountAfter.end() ? -1 : static_cast<Id>(it - this->CountAfter.begin());
}

//------------------------------------------------------------------------------
Id CollapseSchedule::NextRemovingStep(Id steps) const
{
  const Id now = this->CountAfter[steps];
  const auto it = std::partition_point(this->CountAfter.begin() + steps + 1, this->CountAfter.end(),
    [now](Id left) { return left == now; });
  return it == this->CountAfter.end() ? -1 : static_cast<Id>(it - this->CountAfter.begin());
}

} // namespace meshlod
