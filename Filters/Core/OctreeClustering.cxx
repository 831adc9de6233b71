// The octree clustering (OctreeClustering.h): the public class; the work is in the files
// listed in OctreeClusteringInternals.h.
#include "OctreeClusteringInternals.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace meshlod
{
using namespace octree;

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
  ClusterTreeOptions options;
  options.BoundaryWeight = impl.Options.BoundaryWeight;
  options.PlacementTolerance = impl.Options.PlacementTolerance;
  impl.Tree.Build(impl.Mesh, impl.Topology, options);
  const Id ni = impl.Tree.NumberOfInternalNodes();
  impl.State.assign(ni, NodeState::NotEvaluated);
  impl.RepSlot.assign(ni, InvalidId);
  impl.Reps.clear();
  impl.Thr.resize(ni);
  vtkSMPTools::For(0,
    ni,
    [&](Id begin, Id end)
    {
      for (Id i = begin; i < end; ++i)
      {
        impl.UpdateThreshold(i);
      }
    });

  // Level 0 is the input itself.
  impl.CurrentTriangles.clear();
  impl.CurrentLevelZero.clear();
  impl.PointNode.clear();
  impl.PointVertexCount.clear();
  impl.ClusterOfVertex.assign(impl.NV, InvalidId);
  impl.CurrentEpsilon = 0.0;
}

bool OctreeClustering::MakeLevel(double epsilon, ClusterLevel& level)
{
  epsilon = std::max(epsilon, this->Impl->CurrentEpsilon);
  if (this->Impl->TryLevel(epsilon, level) == 0)
  {
    return false;
  }
  this->Impl->Commit(level);
  return true;
}

bool OctreeClustering::MakeLevelForTriangleCount(Id targetTriangles, ClusterLevel& level)
{
  Internals& impl = *this->Impl;
  if (targetTriangles >= impl.PreviousTriangles())
  {
    // A level never refines: asked for at least what the current level has, it is the current
    // level again. At the input, even epsilon 0 would merge clusters of zero error (an exactly
    // flat region): a negative epsilon merges nothing.
    const double epsilon = impl.AtInput() ? -1.0 : impl.CurrentEpsilon;
    if (impl.TryLevel(epsilon, level) == 0)
    {
      return false;
    }
    level.Epsilon = std::max(0.0, epsilon); // the next searches start from it
    impl.Commit(level);
    return true;
  }
  const Id tolerance = std::max<Id>(2, targetTriangles / 500);
  // The estimate NT - (triangles that degenerate in collapsed nodes) ignores duplicates: aim off
  // by the difference a trial level shows, a few times.
  Id aim = targetTriangles;
  ClusterLevel best, trial;
  Id bestCount = 0;
  bool haveBest = false;
  for (int round = 0; round < 3; ++round)
  {
    const double epsilon = impl.SearchEpsilon(aim, std::max<Id>(1, tolerance / 2));
    const Id count = impl.TryLevel(epsilon, trial);
    if (count > 0)
    {
      const Id error = std::abs(count - targetTriangles);
      const Id bestError = std::abs(bestCount - targetTriangles);
      if (!haveBest || error < bestError)
      {
        best = std::move(trial);
        bestCount = count;
        haveBest = true;
      }
    }
    if (std::abs(count - targetTriangles) <= tolerance || count == 0 ||
      epsilon >= std::numeric_limits<float>::max())
    {
      break;
    }
    impl.ComputeActivation();
    aim = static_cast<Id>(
      std::max<std::int64_t>(1, targetTriangles + (impl.EstimateAt(epsilon) - count)));
  }
  if (!haveBest)
  {
    return false;
  }
  level = std::move(best);
  impl.Commit(level);
  return true;
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
    tree.RelatedQuadric(tree.NV + i, q, nullptr, nullptr);
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
