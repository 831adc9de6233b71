// RunTriangleCollapse: the schedule chosen by the options, on the engine of Collapser.h.
#include "TriangleCollapse.h"

#include "Collapser.h"

namespace meshlod
{
//------------------------------------------------------------------------------
TriangleCollapseResult RunTriangleCollapse(TriangleMesh mesh, TriangleTopology topology,
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

} // namespace meshlod
