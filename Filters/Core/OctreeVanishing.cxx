// Octree clustering: what a level would make vanish, small closed pieces far from its surface and
// holes closed up (see OctreeClusteringInternals.h).
#include "FreshMemory.h"
#include "GroupByKey.h"
#include "OctreeClusteringInternals.h"
#include "TriangulationFlips.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <utility>

namespace meshlod
{
using namespace octree;

namespace
{
// A connected piece that keeps no triangle may vanish when the level's surface comes within
// this many times the epsilon of all of it (MarkFarVanishing).
constexpr double VanishingReach = 2.0;

// An axis-aligned box as { lo[3], hi[3] }: empty, then grown point by point.
void ClearBox(double* box)
{
  constexpr double Huge = std::numeric_limits<double>::max();
  std::fill_n(box, 3, Huge);
  std::fill_n(box + 3, 3, -Huge);
}

void GrowBox(double* box, const double x[3])
{
  for (int c = 0; c < 3; ++c)
  {
    box[c] = std::min(box[c], x[c]);
    box[3 + c] = std::max(box[3 + c], x[c]);
  }
}

// The kept triangles of each cluster: those of cluster k are around[offsets[k] .. offsets[k + 1]).
void GroupKeptTriangles(const Synthesis& s, std::vector<Id>& offsets, std::vector<Id>& around)
{
  const Id kept = static_cast<Id>(s.From.size());
  GroupByKey(
    s.Cut.size(),
    [&](auto&& emit)
    {
      for (Id j = 0; j < kept; ++j)
      {
        for (int c = 0; c < 3 && !s.Duplicate[j]; ++c)
        {
          emit(s.Triangles[3 * j + c], j);
        }
      }
    },
    offsets, around);
}

// Whether a kept triangle of cluster k (GroupKeptTriangles) lies within `within` of x.
bool NearKeptTriangle(const Synthesis& s, const std::vector<Id>& offsets,
  const std::vector<Id>& around, Id k, const double x[3], double within)
{
  for (Id i = offsets[k]; i < offsets[k + 1]; ++i)
  {
    const Id* tri = s.Triangles.data() + 3 * around[i];
    double closest[3];
    const double d2 = ClosestPointOnTriangle(x, s.Reps.data() + 3 * tri[0],
      s.Reps.data() + 3 * tri[1], s.Reps.data() + 3 * tri[2], closest);
    if (d2 <= within * within)
    {
      return true;
    }
  }
  return false;
}

// The clusters that keep a triangle (one that is not a duplicate).
std::vector<unsigned char> AliveClusters(const Synthesis& s)
{
  const Id kept = static_cast<Id>(s.From.size());
  const Id clusters = static_cast<Id>(s.Cut.size());
  std::vector<unsigned char> alive = FreshVector<unsigned char>(clusters, 0);
  for (Id j = 0; j < kept; ++j)
  {
    if (!s.Duplicate[j])
    {
      const Id* tri = s.Triangles.data() + 3 * j;
      alive[tri[0]] = alive[tri[1]] = alive[tri[2]] = 1;
    }
  }
  return alive;
}
} // namespace

//------------------------------------------------------------------------------
// The previous level's points in clusters that keep triangles, in a grid of cells
// VanishingReach * epsilon wide, sorted by cell: the kept triangles around such points within
// reach of a piece's centre (found in the 27 cells around it) are the surface that may take
// the piece's place. (The kept points alone are too sparse to judge by: a speck a fifth of its
// radius above a sphere lay farther than twice the epsilon from every one.)
struct OctreeClustering::Internals::KeptSurfaceGrid
{
  using Cell = std::array<std::int64_t, 3>;
  const double* Centre; // the tree's
  double Reach;         // VanishingReach * epsilon
  std::vector<std::pair<Cell, Id>> Points;
  std::vector<Id> Offsets, Around; // the kept triangles of each cluster

  KeptSurfaceGrid(const double* centre, double reach)
    : Centre(centre)
    , Reach(reach)
  {
  }
  // The quotient is clamped before the cast: an epsilon of 1e-20 of the diagonal puts points
  // 1e20 cells away, beyond any integer (undefined in C++). Clamping keeps neighbouring cells
  // neighbours (it never widens a gap), so the 27 cells around a point still hold every point
  // within reach of it, the far ones then possibly among them, which the distance test drops.
  Cell CellOf(const double* x) const
  {
    constexpr double Farthest = 4e18; // cells up to one beyond it still fit in 64 bits
    Cell cell;
    for (int c = 0; c < 3; ++c)
    {
      const double q = std::floor((x[c] - this->Centre[c]) / this->Reach);
      cell[c] = static_cast<std::int64_t>(std::max(-Farthest, std::min(Farthest, q)));
    }
    return cell;
  }
};

//------------------------------------------------------------------------------
// Vanishing pieces: a connected piece of the previous level of which no cluster keeps a
// triangle (a small closed surface merged whole) leaves its input as far from the level as the
// nearest surface that stays, which no cluster's error bounds: merged into a cluster of the
// error of its own size, a blob of the wavelet isosurface (vtkRTAnalyticSource) vanished 5.3%
// of the diagonal away from the rest, where the level's clusters erred by 1.4% at most. Such a
// piece is let go only when the level's kept triangles come within VanishingReach times the
// epsilon of all of it (its centre's distance to the nearest of them plus its radius: a speck
// of a noisy volume next to the surface); otherwise its changed clusters are marked, as for a
// fold, for this trial only (TryLevel lifts the marks after it: a larger epsilon, whose level
// lies farther from the input everywhere, may let the piece go).
Id OctreeClustering::Internals::MarkFarVanishing(Synthesis& s, double epsilon)
{
  // A single piece can only vanish with the whole level: then it is as far from the (empty)
  // level as can be, and is kept too (a thin closed cone, whose cross-section fits in one
  // cluster, kept nothing and ended the hierarchy at level 0).
  const bool keepsTriangles =
    std::find(s.Duplicate.begin(), s.Duplicate.end(), 0) != s.Duplicate.end();
  if (this->PreviousPieces == 0 || (this->PreviousPieces == 1 && keepsTriangles))
  {
    return 0;
  }
  const std::vector<unsigned char> alive = AliveClusters(s);
  std::vector<Id> slot;
  const std::vector<std::uint32_t> vanishing = this->VanishingPieces(s, alive, slot);
  if (vanishing.empty())
  {
    return 0;
  }
  const std::vector<double> box = this->VanishingBoxes(slot, vanishing.size());
  const double reach = VanishingReach * epsilon;
  KeptSurfaceGrid grid(this->Tree.Centre, reach);
  if (reach > 0.0)
  {
    this->FillKeptSurfaceGrid(s, alive, grid);
  }
  std::vector<unsigned char> refused(vanishing.size(), 0);
  bool any = false;
  for (std::size_t i = 0; i < vanishing.size(); ++i)
  {
    const double* b = box.data() + 6 * i;
    const double centre[3] = { 0.5 * (b[0] + b[3]), 0.5 * (b[1] + b[4]), 0.5 * (b[2] + b[5]) };
    const double radius = 0.5 * BoxDiagonal(b, b + 3);
    if (!(radius > 0.0))
    {
      continue; // all its points at one place: nothing is lost
    }
    const bool near = radius < reach && this->NearKeptSurface(s, grid, centre, radius);
    refused[i] = near ? 0 : 1;
    any = any || !near;
  }
  if (!any)
  {
    return 0;
  }
  return this->MarkForTrial(s, this->ClustersOfRefusedPieces(s, slot, refused));
}

//------------------------------------------------------------------------------
// The pieces of the previous level that had triangles and keep none (`alive`: the clusters that
// keep a triangle), in order; `slot` maps each piece to its place among them (InvalidId for the
// others).
std::vector<std::uint32_t> OctreeClustering::Internals::VanishingPieces(
  const Synthesis& s, const std::vector<unsigned char>& alive, std::vector<Id>& slot) const
{
  const std::uint32_t pieces = this->PreviousPieces;
  // 1: had triangles in the previous level; 2: keeps some.
  std::vector<unsigned char> state(pieces, 0);
  const Id previousTriangles = this->PreviousTriangles();
  const Id* prev = this->PreviousTriangleData();
  for (Id t = 0; t < previousTriangles; ++t)
  {
    state[this->PieceOf(prev[3 * t])] = 1;
  }
  const Id previousPoints = this->PreviousPoints();
  for (Id p = 0; p < previousPoints; ++p)
  {
    if (alive[s.PointCluster[p]])
    {
      state[this->PieceOf(p)] = 2;
    }
  }
  std::vector<std::uint32_t> vanishing;
  slot.assign(pieces, InvalidId);
  for (std::uint32_t piece = 0; piece < pieces; ++piece)
  {
    if (state[piece] == 1)
    {
      slot[piece] = static_cast<Id>(vanishing.size());
      vanishing.push_back(piece);
    }
  }
  return vanishing;
}

//------------------------------------------------------------------------------
// The bounding box of each vanishing piece's previous points, 6 numbers each (`count` pieces,
// placed by `slot`: VanishingPieces).
std::vector<double> OctreeClustering::Internals::VanishingBoxes(
  const std::vector<Id>& slot, std::size_t count) const
{
  std::vector<double> box(6 * count);
  for (std::size_t i = 0; i < count; ++i)
  {
    ClearBox(box.data() + 6 * i);
  }
  const Id previousPoints = this->PreviousPoints();
  for (Id p = 0; p < previousPoints; ++p)
  {
    const Id i = slot[this->PieceOf(p)];
    if (i == InvalidId)
    {
      continue;
    }
    double x[3];
    this->RepresentativeOf(this->NodeOfPoint(p), x);
    GrowBox(box.data() + 6 * i, x);
  }
  return box;
}

//------------------------------------------------------------------------------
// The grid's points (those of the clusters that keep a triangle, `alive`) and the kept triangles
// of each cluster; only with a positive reach (cells of no width have no use).
void OctreeClustering::Internals::FillKeptSurfaceGrid(
  const Synthesis& s, const std::vector<unsigned char>& alive, KeptSurfaceGrid& grid) const
{
  const Id previousPoints = this->PreviousPoints();
  for (Id p = 0; p < previousPoints; ++p)
  {
    if (alive[s.PointCluster[p]])
    {
      double x[3];
      this->RepresentativeOf(this->NodeOfPoint(p), x);
      grid.Points.emplace_back(grid.CellOf(x), p);
    }
  }
  std::sort(grid.Points.begin(), grid.Points.end());
  GroupKeptTriangles(s, grid.Offsets, grid.Around);
}

//------------------------------------------------------------------------------
// Whether the kept triangles come within the grid's reach of all of a piece of the given centre
// and radius (below the reach): one of them within the reach less the radius of its centre,
// around a grid point within the reach of it.
bool OctreeClustering::Internals::NearKeptSurface(const Synthesis& s,
  const KeptSurfaceGrid& grid,
  const double centre[3],
  double radius) const
{
  using Cell = KeptSurfaceGrid::Cell;
  const double reach = grid.Reach;
  bool near = false;
  const Cell home = grid.CellOf(centre);
  for (int n = 0; n < 27 && !near; ++n)
  {
    const Cell cell = { home[0] + n % 3 - 1, home[1] + (n / 3) % 3 - 1, home[2] + n / 9 - 1 };
    auto it = std::lower_bound(grid.Points.begin(), grid.Points.end(), std::make_pair(cell, Id(0)));
    for (; it != grid.Points.end() && it->first == cell && !near; ++it)
    {
      double x[3];
      this->RepresentativeOf(this->NodeOfPoint(it->second), x);
      near = Distance2(centre, x) <= reach * reach &&
        NearKeptTriangle(
          s, grid.Offsets, grid.Around, s.PointCluster[it->second], centre, reach - radius);
    }
  }
  return near;
}

//------------------------------------------------------------------------------
// The clusters of the previous triangles of the vanishing pieces that are `refused`, three per
// triangle.
std::vector<Id> OctreeClustering::Internals::ClustersOfRefusedPieces(const Synthesis& s,
  const std::vector<Id>& slot,
  const std::vector<unsigned char>& refused) const
{
  std::vector<Id> far;
  const Id previousTriangles = this->PreviousTriangles();
  const Id* prev = this->PreviousTriangleData();
  for (Id t = 0; t < previousTriangles; ++t)
  {
    const Id* tri = prev + 3 * t;
    const Id i = slot[this->PieceOf(tri[0])];
    if (i != InvalidId && refused[i])
    {
      for (int c = 0; c < 3; ++c)
      {
        far.push_back(s.PointCluster[tri[c]]);
      }
    }
  }
  return far;
}

//------------------------------------------------------------------------------
Id OctreeClustering::Internals::MarkForTrial(Synthesis& s, const std::vector<Id>& clusters)
{
  const std::size_t before = this->RefusedNodes.size();
  const Id marked = this->MarkChanged(s, clusters, false);
  // Lifted after the trial (TryLevel): a larger epsilon may let the piece go or the hole close.
  // They move out of RefusedNodes, which lists the refusals that last (ClearRefusals reports
  // whether there are any, and a search is run again without them).
  this->TrialRefusals.insert(
    this->TrialRefusals.end(), this->RefusedNodes.begin() + before, this->RefusedNodes.end());
  this->RefusedNodes.resize(before);
  return marked;
}

//------------------------------------------------------------------------------
// The input's boundary loops, once: the boundary edges joined at their ends (a vertex where two
// loops touch joins them, which only makes the check below more lenient).
void OctreeClustering::Internals::LabelHoles()
{
  this->HoleOffsets.clear();
  this->HoleVertices.clear();
  if (!this->Options.PreserveTopology)
  {
    return;
  }
  std::vector<Id> up;
  this->ForEachBoundaryEdge([&](Id from, Id to) {
    if (up.empty())
    {
      up.resize(this->NV);
      std::iota(up.begin(), up.end(), Id(0));
    }
    const Id a = FindRoot(up, from), b = FindRoot(up, to);
    up[std::max(a, b)] = std::min(a, b);
  });
  if (up.empty())
  {
    return;
  }
  // Boundary vertices are those joined to another or joining one; grouped by their loop's root
  // (each vertex's root written down: halving the paths does not flatten every link).
  std::vector<unsigned char> onBoundary(this->NV, 0);
  for (Id v = 0; v < this->NV; ++v)
  {
    const Id root = FindRoot(up, v);
    if (root != v)
    {
      onBoundary[v] = onBoundary[root] = 1;
    }
    up[v] = root;
  }
  GroupByKey(
    static_cast<std::size_t>(this->NV),
    [&](auto&& emit)
    {
      for (Id v = 0; v < this->NV; ++v)
      {
        if (onBoundary[v])
        {
          emit(up[v], v);
        }
      }
    },
    this->HoleOffsets, this->HoleVertices);
  // Keep the offsets of non-empty groups only.
  std::vector<Id> offsets{ 0 };
  for (std::size_t i = 0; i + 1 < this->HoleOffsets.size(); ++i)
  {
    if (this->HoleOffsets[i + 1] > this->HoleOffsets[i])
    {
      offsets.push_back(this->HoleOffsets[i + 1]);
    }
  }
  this->HoleOffsets.swap(offsets);
  const Id holes = static_cast<Id>(this->HoleOffsets.size()) - 1;
  this->HoleRadius.assign(holes, 0.0);
  for (Id h = 0; h < holes; ++h)
  {
    double box[6];
    ClearBox(box);
    for (Id i = this->HoleOffsets[h]; i < this->HoleOffsets[h + 1]; ++i)
    {
      GrowBox(box, this->Mesh.Point(this->HoleVertices[i]));
    }
    this->HoleRadius[h] = 0.5 * BoxDiagonal(box, box + 3);
  }
}

//------------------------------------------------------------------------------
// Holes closed up: a boundary loop of the input whose vertices fall into fewer than three
// clusters has no edge left; the hole is gone (a cluster caps it) and the input's boundary there
// is as far from the level as the surface that caps it. On the wavelet isosurface
// (vtkRTAnalyticSource, open at the volume's faces) asked for 1%, 11 of its 39 loops closed,
// the input 3.7% of the diagonal from the level at one, whose clusters erred by 1.4% at most.
// A loop may close only when each of its vertices lies within VanishingReach times the epsilon
// of a kept triangle of its cluster (as a vanishing piece may go); otherwise the changed
// clusters of its vertices are marked, as for a fold, for this trial only. (Kept open at any
// epsilon, the 32 loops of a smaller wavelet isosurface held its level asked for 1% at 10%;
// let close when small next to the epsilon, the large wavelet's tube ends still closed far from
// the level.)
Id OctreeClustering::Internals::MarkClosedHoles(Synthesis& s, double epsilon)
{
  const Id holes = static_cast<Id>(this->HoleOffsets.size()) - 1;
  const double reach = VanishingReach * epsilon;
  std::vector<Id> closed, offsets, around;
  for (Id h = 0; h < holes; ++h)
  {
    const Id first = this->HoleOffsets[h], last = this->HoleOffsets[h + 1];
    Id seen[2] = { InvalidId, InvalidId };
    int distinct = 0;
    for (Id i = first; i < last && distinct < 3; ++i)
    {
      const Id k = this->ClusterOfVertex[this->HoleVertices[i]];
      if (distinct == 0 || (k != seen[0] && (distinct == 1 || k != seen[1])))
      {
        if (distinct < 2)
        {
          seen[distinct] = k;
        }
        ++distinct;
      }
    }
    if (distinct >= 3 || last - first < 3)
    {
      continue;
    }
    bool near = this->HoleRadius[h] <= reach;
    if (near && offsets.empty())
    {
      GroupKeptTriangles(s, offsets, around);
    }
    for (Id i = first; i < last && near; ++i)
    {
      const Id v = this->HoleVertices[i];
      near = NearKeptTriangle(s, offsets, around, this->ClusterOfVertex[v], this->Mesh.Point(v), reach);
    }
    if (!near)
    {
      for (Id i = first; i < last; ++i)
      {
        closed.push_back(this->ClusterOfVertex[this->HoleVertices[i]]);
      }
    }
  }
  return closed.empty() ? 0 : this->MarkForTrial(s, closed);
}

} // namespace meshlod
