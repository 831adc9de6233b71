// The octree clustering (OctreeClustering.h): the public class; the work is in the files
// listed in OctreeClusteringInternals.h.
#include "FreshMemory.h"
#include "OctreeClusteringInternals.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace meshlod
{
using namespace octree;

namespace
{
// The corrected aim of the count search never falls below the target over this, and a level
// with fewer triangles than that is searched again without the earlier levels' fold refusals.
constexpr Id MinimumAimFraction = 4;

// How far a count is from a target, as a ratio: 2 triangles for a target of 1555 is worse than
// 17,000.
double Miss(Id count, Id target)
{
  return std::abs(std::log(static_cast<double>(count) / static_cast<double>(target)));
}
}

//------------------------------------------------------------------------------
OctreeClustering::OctreeClustering(const TriangleMesh& mesh,
  const TriangleTopology& topology,
  const OctreeClusteringOptions& options)
  : Impl(new Internals(mesh, topology, options))
{
}

OctreeClustering::~OctreeClustering()
{
  delete this->Impl;
}

void OctreeClustering::BuildTree()
{
  Internals& impl = *this->Impl;
  // Level 0 is the input itself (empty vectors stand for it); its pieces and their handles
  // are measured before the tree is built, so that the measuring's working memory comes and
  // goes before the tree's.
  impl.CurrentTriangles.clear();
  impl.CurrentLevelZero.clear();
  impl.PointNode.clear();
  impl.PointVertexCount.clear();
  impl.LabelPreviousPieces();
  ClusterTreeOptions options;
  options.BoundaryWeight = impl.Options.BoundaryWeight;
  options.PlacementTolerance = impl.Options.PlacementTolerance;
  impl.Tree.Build(impl.Mesh, impl.Topology, options);
  const Id ni = impl.Tree.NumberOfInternalNodes();
  AssignFresh(impl.State, ni, NodeState::NotEvaluated);
  AssignFresh(impl.Refused, ni, 0);
  impl.RefusedNodes.clear();
  AssignFresh(impl.RepSlot, ni, InvalidId);
  impl.RepBlocks.clear();
  impl.RepCount = 0;
  ResizeFresh(impl.Thr, ni);
  vtkSMPTools::For(0,
    ni,
    [&](Id begin, Id end)
    {
      for (Id i = begin; i < end; ++i)
      {
        impl.UpdateThreshold(i);
      }
    });

  AssignFresh(impl.ClusterOfVertex, impl.NV, InvalidId);
  impl.CurrentEpsilon = 0.0;
  impl.LabelHoles();
  impl.LabelTips();
}

bool OctreeClustering::MakeLevel(double epsilon, ClusterLevel& level)
{
  Internals& impl = *this->Impl;
  epsilon = std::max(epsilon, impl.CurrentEpsilon);
  const Id refusals = impl.HandleRefusals;
  if (impl.TryLevel(epsilon, level) == 0)
  {
    if (impl.HandleRefusals == refusals)
    {
      return false;
    }
    // The epsilon closes a handle: the largest smaller one that does not, else the current
    // level again (level.Epsilon says which was taken).
    impl.EmptyEpsilon = epsilon;
    if (impl.LastNonEmpty(level) == 0 && impl.RepeatCurrentLevel(level) == 0)
    {
      return false;
    }
  }
  impl.Commit(level);
  return true;
}

void OctreeClustering::FlipEdges(ClusterLevel& level, const ClusterLevel* next) const
{
  const bool follows = next != nullptr &&
    next->Target.size() == static_cast<size_t>(level.Mesh.GetNumberOfPoints());
  this->Impl->FlipLevelEdges(level, follows ? next->Target.data() : nullptr);
}

bool OctreeClustering::MakeLevelForTriangleCount(Id targetTriangles, ClusterLevel& level)
{
  Internals& impl = *this->Impl;
  if (targetTriangles >= impl.PreviousTriangles())
  {
    // A level never refines: asked for at least what the current level has, it is the current
    // level again.
    if (impl.RepeatCurrentLevel(level) == 0)
    {
      return false;
    }
    impl.Commit(level);
    return true;
  }
  const Id refusals = impl.HandleRefusals;
  ClusterLevel best;
  Id bestCount = impl.SearchLevel(targetTriangles, best);
  if (bestCount < targetTriangles / MinimumAimFraction && impl.ClearRefusals())
  {
    // Far too few (or none): the earlier levels' fold refusals left nothing to merge but large
    // nodes. Without them (the clusters around them are coarser now) the search may do better.
    ClusterLevel retry;
    const Id count = impl.SearchLevel(targetTriangles, retry);
    if (count > 0 && (bestCount == 0 || Miss(count, targetTriangles) < Miss(bestCount, targetTriangles)))
    {
      best = std::move(retry);
      bestCount = count;
    }
  }
  if (bestCount == 0 || bestCount >= impl.PreviousTriangles())
  {
    // None, or no fewer triangles than the level before: the trials near the aim were all
    // refused (a Klein bottle of 9,600 triangles asked for 48 got 9,600 back).
    // The coarsest level that keeps triangles, if nearer.
    ClusterLevel coarsest;
    const Id count = impl.LastNonEmpty(coarsest);
    if (count > 0 &&
      (bestCount == 0 || Miss(count, targetTriangles) < Miss(bestCount, targetTriangles)))
    {
      best = std::move(coarsest);
      bestCount = count;
    }
  }
  if (bestCount == 0 && impl.HandleRefusals > refusals)
  {
    // Every level with fewer triangles closed a handle.
    bestCount = impl.RepeatCurrentLevel(best);
  }
  if (bestCount == 0)
  {
    return false;
  }
  if (bestCount > targetTriangles + targetTriangles / 4)
  {
    bestCount = impl.BackOff(bestCount, best);
  }
  level = std::move(best);
  impl.Commit(level);
  return true;
}

//------------------------------------------------------------------------------
Id OctreeClustering::Internals::BackOff(Id count, ClusterLevel& best)
{
  // A target the surface cannot reach (junctions of curves never merge, folds are refused):
  // the search ends at an epsilon that merges whatever may merge, far beyond what that count
  // needs. On the surfaces of a segmented volume (three sheets along curves) that level had
  // 13 times the RMS distance of one with a tenth more triangles. Bisect the epsilon (on a log
  // scale, to within 5%) for the smallest that keeps about as few: at most a tenth more, or at
  // most half more when its error is under a quarter of the search level's (the count is on a
  // plateau: on the segmented volume, curves that may merge no further kept 2,423 triangles at
  // 4.6% Hausdorff distance, 3,245 at 0.79%; where the count follows the error, as on a rough
  // surface, a quarter of the error costs about four times the triangles, and only the tenth
  // applies). Never more than three quarters of what the level removes from the previous one
  // come back (so that it still makes progress). An epsilon beyond the octree's size merges
  // all it ever will (the search's can be the largest float); four decades below the search's,
  // and below the previous level's, it merges next to nothing.
  //
  // A level with more triangles is also taken when it is far more accurate for its count than
  // the best so far: error times the square root of the count (about constant where the error
  // follows the count, as a surface's chord error does) under a tenth. On a subdivided
  // icosahedron asked for 1%, whose clusters across its edges cut the corners, 390 triangles
  // at 8% Hausdorff distance became 864 at none. (At a half, rough surfaces went back most of
  // the way to their input: a noisy sphere asked for 10% kept 76,388 of 78,168 triangles.) At
  // most four times the search's count: where every level near the count is coarse, more
  // triangles are always far more accurate (a Klein bottle of 9,600 triangles asked for 64,
  // whose search found 100, went back to 6,266).
  const Id previous = this->PreviousTriangles();
  const Id giveBack = 3 * (previous - count) / 4;
  const Id limit = count + giveBack; // of the search's count, not of a level taken since
  const Id farthest = std::min(limit, 4 * count); // for an accurate level (see below)
  const Id close = count + std::min(count / 10, giveBack);
  const Id plateau = count + std::min(count / 2, giveBack);
  const double plateauError = best.EstimatedError / 4.0;
  auto accuracy = [](const ClusterLevel& level, Id triangles)
  { return level.EstimatedError * std::sqrt(static_cast<double>(triangles)); };
  double high = std::min(best.Epsilon, 2.0 * this->Tree.Size);
  double low = std::max(this->CurrentEpsilon, 1e-4 * high);
  ClusterLevel trial;
  for (int step = 0; step < 8 && high > 1.05 * low; ++step)
  {
    const double middle = std::sqrt(low * high);
    const Id triangles = this->TryLevel(middle, trial);
    const bool accurate = triangles > 0 && triangles <= farthest &&
      accuracy(trial, triangles) < 0.1 * accuracy(best, count);
    if (triangles > 0 &&
      (triangles <= close || (triangles <= plateau && trial.EstimatedError <= plateauError) ||
        accurate))
    {
      best = std::move(trial);
      count = triangles;
      high = middle;
      if (!(best.EstimatedError > 0.0))
      {
        break; // smaller epsilons only keep more triangles at no less error
      }
    }
    else if (triangles == 0 || triangles <= plateau)
    {
      // Merged away whole, or few enough triangles but at too large an error: the epsilon is
      // still too large.
      high = middle;
    }
    else
    {
      low = middle;
    }
  }
  return count;
}

//------------------------------------------------------------------------------
Id OctreeClustering::Internals::LastNonEmpty(ClusterLevel& best)
{
  // Down from the smallest epsilon that kept nothing by halves to the first that keeps some,
  // then bisect on a log scale between the two; never below the current level's epsilon (it
  // keeps the current level), nor four decades below. (Asked for 50 triangles, a noisy sphere
  // of 1,680 got no level at all while 200 gave 1,650.) Not a bisection from the start: the
  // epsilons whose levels are refused for a lost handle need not be one interval, and a
  // bisection from the middle of the range can end far below the largest that keeps them all.
  double high = std::min(this->EmptyEpsilon, 2.0 * this->Tree.Size);
  const double floor = std::max(this->CurrentEpsilon, 1e-4 * high);
  double low = 0.0; // the largest epsilon found to keep triangles
  ClusterLevel trial;
  Id count = 0;
  while (count == 0 && high > floor)
  {
    const double epsilon = std::max(0.5 * high, floor);
    count = this->TryLevel(epsilon, trial);
    if (count > 0)
    {
      best = std::move(trial);
      low = epsilon;
    }
    else
    {
      high = epsilon;
    }
  }
  for (int step = 0; count > 0 && step < 6 && high > 1.02 * low; ++step)
  {
    const double middle = std::sqrt(low * high);
    const Id triangles = this->TryLevel(middle, trial);
    if (triangles > 0)
    {
      best = std::move(trial);
      count = triangles;
      low = middle;
    }
    else
    {
      high = middle;
    }
  }
  return count;
}

//------------------------------------------------------------------------------
Id OctreeClustering::Internals::SearchLevel(Id targetTriangles, ClusterLevel& best)
{
  const Id tolerance = std::max<Id>(2, targetTriangles / 500);
  // The estimate NT - (triangles that degenerate in collapsed nodes) ignores duplicates and the
  // clusters split again to remove folds: aim off by the difference a trial level shows, a few
  // times. On a rough surface the folds can add back more than the whole target; the aim then
  // stays at a fraction of the target (aiming at nothing would cut the octree at its roots).
  const Id lowestAim = std::max<Id>(1, targetTriangles / MinimumAimFraction);
  Id aim = targetTriangles;
  ClusterLevel trial;
  Id bestCount = 0;
  this->EmptyEpsilon = std::numeric_limits<double>::infinity();
  for (int round = 0; round < 3; ++round)
  {
    const double epsilon = this->SearchEpsilon(aim, std::max<Id>(1, tolerance / 2));
    const Id count = this->TryLevel(epsilon, trial);
    if (count == 0)
    {
      this->EmptyEpsilon = std::min(this->EmptyEpsilon, epsilon);
    }
    if (count > 0 &&
      (bestCount == 0 || Miss(count, targetTriangles) < Miss(bestCount, targetTriangles)))
    {
      best = std::move(trial);
      bestCount = count;
    }
    // (A trial that keeps nothing, a closed surface merged whole, corrects the aim upwards.)
    if (std::abs(count - targetTriangles) <= tolerance ||
      epsilon >= std::numeric_limits<float>::max())
    {
      break;
    }
    this->ComputeActivation();
    aim = static_cast<Id>(
      std::max<std::int64_t>(lowestAim, targetTriangles + (this->EstimateAt(epsilon) - count)));
  }
  return bestCount;
}

Id OctreeClustering::GetCurrentTriangleCount() const
{
  return this->Impl->PreviousTriangles();
}

Id OctreeClustering::GetNumberOfInternalNodes() const
{
  return this->Impl->Tree.NumberOfInternalNodes();
}

Id OctreeClustering::GetNumberOfRoots() const
{
  const ClusterTree& tree = this->Impl->Tree;
  Id roots = 0;
  for (Id node = 0; node < tree.NV + tree.NumberOfInternalNodes(); ++node)
  {
    roots += tree.Parent(node) == InvalidId ? 1 : 0;
  }
  return roots;
}

int OctreeClustering::GetTreeDepth() const
{
  return this->Impl->Tree.Depth;
}

Id OctreeClustering::GetNumberOfEvaluatedNodes() const
{
  return this->Impl->Evaluated;
}

const ClusterTree& OctreeClustering::GetTree() const
{
  return this->Impl->Tree;
}

//------------------------------------------------------------------------------
double OctreeClustering::CheckNodeQuadrics(Id count) const
{
  // The tree keeps e1 only: recompute it from the related triangle set of a few nodes and
  // compare (a wrong inclusion-exclusion would show as a different e1).
  const Internals& impl = *this->Impl;
  const ClusterTree& tree = impl.Tree;
  const Id ni = tree.NumberOfInternalNodes();
  const Id stride = std::max<Id>(1, ni / std::max<Id>(1, count));
  double worst = 0.0;
  for (Id i = 0; i < ni; i += stride)
  {
    const ClusterNode& n = tree.Nodes[i];
    Quadric q;
    tree.RelatedQuadric(tree.NV + i, q, nullptr);
    double centre[3];
    tree.Centroid(tree.NV + i, centre);
    double rep[3];
    MinimizeQuadric(q, centre, impl.Options.PlacementTolerance, rep);
    const double weight = q.Weight();
    const double e1 = weight > 0.0 ? std::sqrt(q.Evaluate(rep) / weight) : 0.0;
    worst = std::max(worst, std::abs(e1 - n.E1) / tree.Size);
  }
  return worst;
}

} // namespace meshlod
