// CollapseScheduleBuilder (CollapseScheduleBuilder.h): whether a step leaves a valid mesh, its
// target's merged vertex with one fan, and whether it folds a triangle over.
#include "CollapseScheduleBuilder.h"
#include "LinkFan.h"
#include "Vector3.h"

#include <algorithm>

namespace meshlod
{
namespace
{
// A triangle faces a direction m when its normal n has n . m > FacingTolerance |m|^2 (both are
// twice-area vectors): three corners on a line up to rounding do not.
constexpr double FacingTolerance = 1e-12;
} // namespace

//------------------------------------------------------------------------------
int CollapseScheduleBuilder::CountSheets(Id p)
{
  this->Neighbours.clear();
  for (Id i = this->Adjacency.Begin(p); i < this->Adjacency.End(p); ++i)
  {
    const Id* tri = this->Triangle(this->Adjacency.Triangles[i]);
    for (int k = 0; k < 3; ++k)
    {
      if (tri[k] != p)
      {
        this->Neighbours.push_back(tri[k]);
      }
    }
  }
  std::sort(this->Neighbours.begin(), this->Neighbours.end());
  int most = 0;
  ForEachRun(this->Neighbours, [&](int triangles) { most = std::max(most, triangles); });
  return most > 2 ? most : 1;
}

int CollapseScheduleBuilder::SheetsAt(Id t)
{
  if (this->SheetsOf[t] == 0)
  {
    this->SheetsOf[t] = 1;
    for (Id i = this->TargetOffsets[t]; i < this->TargetOffsets[t + 1]; ++i)
    {
      this->SheetsOf[t] = std::max(this->SheetsOf[t], this->CountSheets(this->TargetPoints[i]));
    }
  }
  return this->SheetsOf[t];
}

//------------------------------------------------------------------------------
bool CollapseScheduleBuilder::OtherFanIsValid(Id t)
{
  const int sheets = this->SheetsAt(t);
  if (sheets > 2)
  {
    return LinkHasShape(this->From, this->To, sheets, 2);
  }
  // (The shape first: on a consistent mesh it fails where the directed test did, and the
  // orientation test sorts the whole star.)
  return (LinkHasShape(this->From, this->To, 1, 2) || LinkHasShape(this->From, this->To, 2, 0)) &&
    HasRepeatedDirectedEdge(
      this->Triangles, this->Adjacency, this->Members, this->Around, this->Directed);
}

bool CollapseScheduleBuilder::FanIsValid(std::vector<Id>& classes, Id t, Id root)
{
  // (HasOneFan leaves the merged vertex's link edges in From and To.)
  return HasOneFan(
           this->Triangles, this->Adjacency, classes, this->Members, root, this->From, this->To) ||
    this->OtherFanIsValid(t);
}

// Whether target t's vertex in the next level (every point merged) passes that test. A
// level with non-manifold vertices (vertex clustering with PreserveTopology off) has
// targets that no step can give one fan: they are not held against a step, or every step
// after the first to reach one could not be stopped at. Asked only when a step fails, and
// cached; on a manifold level the answer is yes, except where two triangles of this level
// become the same triangle of the next (which keeps one of them): such a target is let
// through as well, with the doubled triangle until its transition ends.
bool CollapseScheduleBuilder::ValidInNextLevel(Id t)
{
  if (this->NextLevelValid[t] == 0)
  {
    if (this->Merged.empty())
    {
      this->Merged.resize(this->NumberOfPoints);
      for (Id p = 0; p < this->NumberOfPoints; ++p)
      {
        this->Merged[p] = this->TargetPoints[this->TargetOffsets[this->Target[p]]];
      }
    }
    this->Members.assign(this->TargetPoints.begin() + this->TargetOffsets[t],
      this->TargetPoints.begin() + this->TargetOffsets[t + 1]);
    this->NextLevelValid[t] =
      this->FanIsValid(this->Merged, t, this->TargetPoints[this->TargetOffsets[t]]) ? 1 : 2;
  }
  return this->NextLevelValid[t] == 1;
}

//------------------------------------------------------------------------------
// The link edge triangle `tri` gives the vertex of class `root`, if any.
bool CollapseScheduleBuilder::LinkEdge(Id tri, Id root, Id& from, Id& to)
{
  const Id* v = this->Triangle(tri);
  const Id c[3] = { FindRoot(this->Parent, v[0]), FindRoot(this->Parent, v[1]),
    FindRoot(this->Parent, v[2]) };
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
}

// Track target t: its link listed from its settled points.
void CollapseScheduleBuilder::Track(Id t)
{
  if (!this->LinkSized)
  {
    this->Link.Reset(this->NumberOfPoints, this->NumberOfTriangles);
    this->LinkSized = true;
  }
  this->Link.Clear();
  this->Tracked = t;
  if (this->SettledOn[t] == Unassigned)
  {
    return;
  }
  const Id root = FindRoot(this->Parent, this->SettledOn[t]);
  for (Id i = this->TargetOffsets[t]; i < this->TargetOffsets[t + 1]; ++i)
  {
    const Id q = this->TargetPoints[i];
    for (Id j = this->Adjacency.Begin(q);
         j < this->Adjacency.End(q) && this->Step[q] != Unassigned; ++j)
    {
      const Id tri = this->Adjacency.Triangles[j];
      Id from, to;
      if (!this->Link.Holds(tri) && this->LinkEdge(tri, root, from, to))
      {
        this->Link.Add(tri, from, to);
      }
    }
  }
}

// Point q (a class of its own until now; a trial may already point it at `root`) joins class
// `root` of the tracked target: the link edges of its triangles change (the held ones are
// removed by triangle, whatever q's class). With `removed`, they are kept there for Leave().
void CollapseScheduleBuilder::Join(Id q, Id root, std::vector<std::array<Id, 3>>* removed)
{
  for (Id j = this->Adjacency.Begin(q); j < this->Adjacency.End(q); ++j)
  {
    const Id tri = this->Adjacency.Triangles[j];
    if (this->Link.Holds(tri))
    {
      const std::pair<Id, Id> e = this->Link.Remove(tri);
      if (removed)
      {
        removed->push_back({ tri, e.first, e.second });
      }
    }
  }
  this->Parent[q] = root;
  for (Id j = this->Adjacency.Begin(q); j < this->Adjacency.End(q); ++j)
  {
    // (A triangle listed twice around q has q twice: degenerate, it gives no edge.)
    const Id tri = this->Adjacency.Triangles[j];
    Id from, to;
    if (!this->Link.Holds(tri) && this->LinkEdge(tri, root, from, to))
    {
      this->Link.Add(tri, from, to);
    }
  }
}

// Undoes Join(q, ..., &removed): q is a class of its own again (an unsettled point always is,
// and no other point's parent is it).
void CollapseScheduleBuilder::Leave(Id q, const std::vector<std::array<Id, 3>>& removed)
{
  for (Id j = this->Adjacency.Begin(q); j < this->Adjacency.End(q); ++j)
  {
    const Id tri = this->Adjacency.Triangles[j];
    if (this->Link.Holds(tri))
    {
      this->Link.Remove(tri);
    }
  }
  this->Parent[q] = q;
  for (const auto& e : removed)
  {
    this->Link.Add(e[0], e[1], e[2]);
  }
}

//------------------------------------------------------------------------------
// Asked when a fan test fails; where no such edge is, the test for a surface without
// consistent orientation cannot pass for any of its points.
bool CollapseScheduleBuilder::MayBeInconsistent(Id t)
{
  if (this->InconsistentAt[t] == 0)
  {
    std::vector<Id> all(this->TargetPoints.begin() + this->TargetOffsets[t],
      this->TargetPoints.begin() + this->TargetOffsets[t + 1]);
    this->InconsistentAt[t] =
      HasRepeatedDirectedEdge(this->Triangles, this->Adjacency, all, this->Around, this->Directed)
      ? 2
      : 1;
  }
  return this->InconsistentAt[t] == 2;
}

// The points settled on target t, and `extra` (when given), into Members.
void CollapseScheduleBuilder::ListMembers(Id t, Id extra)
{
  this->Members.clear();
  for (Id i = this->TargetOffsets[t]; i < this->TargetOffsets[t + 1]; ++i)
  {
    const Id q = this->TargetPoints[i];
    if (q == extra || this->Step[q] != Unassigned)
    {
      this->Members.push_back(q);
    }
  }
}

// FanIsValid for the tracked target t, whose link holds the points settled and `extra`.
bool CollapseScheduleBuilder::TrackedFanIsValid(Id t, Id extra)
{
  if (this->Link.IsOneFan())
  {
    return true;
  }
  if (this->SheetsAt(t) <= 2 && !this->MayBeInconsistent(t))
  {
    return false;
  }
  this->Link.Export(this->From, this->To);
  this->ListMembers(t, extra);
  return this->OtherFanIsValid(t);
}

// Whether the points settled on target t (and `extra`, when given) form one vertex with one
// fan; `extra` must already point at the class root.
bool CollapseScheduleBuilder::TargetHasOneFan(Id t, Id extra)
{
  if (t == this->Tracked)
  {
    bool valid = false;
    if (extra == Unassigned)
    {
      valid = this->TrackedFanIsValid(t, extra);
    }
    else
    {
      this->Undo.clear();
      this->Join(extra, FindRoot(this->Parent, this->SettledOn[t]), &this->Undo);
      valid = this->TrackedFanIsValid(t, extra);
      this->Leave(extra, this->Undo);
    }
    return valid || !this->ValidInNextLevel(t);
  }
  this->ListMembers(t, extra);
  return this->FanIsValid(this->Parent, t, FindRoot(this->Parent, this->SettledOn[t])) ||
    !this->ValidInNextLevel(t);
}

// Whether settling p now leaves a valid mesh (p's target keeps one fan).
bool CollapseScheduleBuilder::ValidWith(Id p)
{
  const Id t = this->Target[p];
  if (this->SettledOn[t] == Unassigned)
  {
    return true; // the first point of its target only moves
  }
  const Id saved = this->Parent[p];
  this->Parent[p] = FindRoot(this->Parent, this->SettledOn[t]);
  const bool valid = this->TargetHasOneFan(t, p);
  this->Parent[p] = saved;
  return valid;
}

//------------------------------------------------------------------------------
// The points of a collapse settling one at a time can fold the triangles around the first ones
// over (an exact-count sphere had triangles facing inwards) or lay three corners on a line (on
// a flat grid's border). A live triangle that faces neither the way it does in level i nor the
// way it does once every point has settled (or has no area) is folded; the join order takes
// points whose join folds nothing around them where it can. (Triangles without area in level i
// itself, kept from the input, are not judged. Refusing to stop at every step that leaves a fold
// anywhere made most counts of a collapse of many points unreachable.)
// Whether triangle tri is live and folded with the settled points, and `extra`, settled.
bool CollapseScheduleBuilder::IsFolded(Id tri, Id extra)
{
  const Id* v = this->Triangle(tri);
  const auto settledNow = [&](Id q) { return q == extra || this->Step[q] != Unassigned; };
  for (int k = 0; k < 3; ++k)
  {
    const Id x = v[k], y = v[(k + 1) % 3];
    if (this->Target[x] == this->Target[y] && settledNow(x) && settledNow(y))
    {
      return false; // gone
    }
  }
  const auto at = [&](int k, bool settled) {
    return (settled ? this->TargetPositions : this->Positions) + 3 * static_cast<size_t>(v[k]);
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
}

// Whether settling p now leaves a folded triangle around it.
bool CollapseScheduleBuilder::FoldsAround(Id p)
{
  for (Id i = this->Adjacency.Begin(p); this->Geometry && i < this->Adjacency.End(p); ++i)
  {
    if (this->IsFolded(this->Adjacency.Triangles[i], p))
    {
      return true;
    }
  }
  return false;
}

} // namespace meshlod
