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
  // The curvature method re-weights a ring beyond each collapse, which the blocks of the
  // partitioned run do not keep apart.
  return options.PartitionedGreedy && options.Method == CollapseMethod::Quadric
    ? collapser.RunPartitionedGreedy()
    : collapser.RunGreedy();
}

} // namespace meshlod
