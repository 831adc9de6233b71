// RunTriangleCollapse: the schedule chosen by the options, on the engine of Collapser.h, on a
// spatially renumbered copy of a mesh whose ids are scattered (SpatialOrder.h).
#include "TriangleCollapse.h"

#include "Collapser.h"
#include "LevelData.h"
#include "SpatialOrder.h"

namespace meshlod
{
namespace
{
TriangleCollapseResult Run(TriangleMesh mesh, TriangleTopology topology,
  const TriangleCollapseOptions& options, const TriangleCollapseCallbacks& callbacks)
{
  Collapser collapser(std::move(mesh), std::move(topology), options, callbacks);
  if (options.Schedule == CollapseSchedule::IndependentSets)
  {
    return collapser.RunIndependentSets();
  }
  // (The partitioned run falls back to the serial one for the curvature method.)
  return options.PartitionedGreedy ? collapser.RunPartitionedGreedy() : collapser.RunGreedy();
}

} // namespace

//------------------------------------------------------------------------------
TriangleCollapseResult RunTriangleCollapse(TriangleMesh mesh, TriangleTopology topology,
  const TriangleCollapseOptions& options, const TriangleCollapseCallbacks& callbacks)
{
  SpatialRenumbering order;
  if (!order.ApplyIfScattered(mesh, topology))
  {
    return Run(std::move(mesh), std::move(topology), options, callbacks);
  }
  // The fits' reads of the caller's points go through the renumbering too.
  TriangleCollapseOptions renumbered = options;
  std::vector<long long> pointIds;
  if (options.InputPointsFloat || options.InputPointsDouble)
  {
    pointIds.resize(order.OldVertex.size());
    for (std::size_t v = 0; v < pointIds.size(); ++v)
    {
      const Id old = order.OldVertex[v];
      pointIds[v] = options.InputPointIds ? options.InputPointIds[old] : old;
    }
    renumbered.InputPointIds = pointIds.data();
  }
  TriangleCollapseCallbacks translated = callbacks;
  if (callbacks.EmitLevel)
  {
    translated.EmitLevel = [&](LevelData& level, LevelRetriangulation& changed) {
      order.NumberBack(level.LevelZeroTriangle, level.Sources.Parents, level.Target, level.Rank);
      callbacks.EmitLevel(level, changed);
      for (Id& t : changed.Triangles)
      {
        t = order.NewTriangle[t];
      }
    };
  }
  return Run(std::move(mesh), std::move(topology), renumbered, translated);
}

} // namespace meshlod
