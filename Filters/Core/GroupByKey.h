// MeshLOD core: items grouped by a small integer key (a stable counting sort) into compressed
// rows, as the octree's synthesis (the triangles and edges of each cluster, the sources of each
// point), the cluster tree's bottom tier (the vertices of each cell), the collapse schedule (the
// points of each target) and the level centring (the samples of each point) build them.
// (VertexTriangleAdjacency::Build fills its rows in parallel, and the cluster tree's children
// come in depth-first order from a walk: each keeps a sort of its own.)
#ifndef meshlod_GroupByKey_h
#define meshlod_GroupByKey_h

#include "FreshMemory.h"

#include <cstddef>
#include <vector>

namespace meshlod
{
/// Groups the items that `forEach` lists by key, keys in [0, keys). forEach(emit) must call
/// emit(key, value) once per item, in the same order each time: it is called twice, to count
/// and to fill. Afterwards row k is values[offsets[k]] .. values[offsets[k + 1] - 1], in the
/// order the items were listed, and offsets[keys] is the number of items. Both vectors are
/// overwritten; large ones are allocated on prepared memory (FreshMemory.h).
template <typename Offset, typename Value, typename ForEach>
void GroupByKey(std::size_t keys, ForEach&& forEach, std::vector<Offset>& offsets,
  std::vector<Value>& values)
{
  AssignFresh(offsets, keys + 1, Offset(0));
  forEach([&](std::size_t key, const Value&) { ++offsets[key + 1]; });
  for (std::size_t k = 0; k < keys; ++k)
  {
    offsets[k + 1] += offsets[k];
  }
  ResizeFresh(values, static_cast<std::size_t>(offsets[keys]));
  // The row starts double as fill cursors: row k is filled from offsets[k] on, which then ends
  // where row k + 1 starts, so shifting the offsets up by one restores them (no cursor array).
  forEach([&](std::size_t key, const Value& value) { values[offsets[key]++] = value; });
  for (std::size_t k = keys; k > 0; --k)
  {
    offsets[k] = offsets[k - 1];
  }
  offsets[0] = 0;
}

} // namespace meshlod

#endif
