// MeshLOD core: items grouped by a small integer key (a stable counting sort) into compressed
// rows, as the octree's synthesis (the triangles and edges of each cluster, the sources of each
// point), the cluster tree's bottom tier (the vertices of each cell), the collapse schedule (the
// points of each target) and the level centring (the samples of each point) build them.
// GroupItemsByKey does the same with threads, for VertexTriangleAdjacency::Build (the triangles
// of each point) and HandleMeasures (the sides of each point). (The cluster tree's children come
// in depth-first order from a walk, and keep a sort of their own.)
#ifndef meshlod_GroupByKey_h
#define meshlod_GroupByKey_h

#include "FreshMemory.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace meshlod
{
namespace group_by_key
{
// offsets[k + 1] holds the size of row k: make offsets[k] the start of row k.
template <typename Offset>
void CountsToRowStarts(std::vector<Offset>& offsets, std::size_t keys)
{
  for (std::size_t k = 0; k < keys; ++k)
  {
    offsets[k + 1] += offsets[k];
  }
}

// The row starts served as fill cursors: row k was filled from offsets[k] on, which then ends
// where row k + 1 starts, so shifting the offsets up by one restores them (no cursor array).
template <typename Offset>
void CursorsToRowStarts(std::vector<Offset>& offsets, std::size_t keys)
{
  for (std::size_t k = keys; k > 0; --k)
  {
    offsets[k] = offsets[k - 1];
  }
  offsets[0] = 0;
}
} // namespace group_by_key

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
  group_by_key::CountsToRowStarts(offsets, keys);
  ResizeFresh(values, static_cast<std::size_t>(offsets[keys]));
  forEach([&](std::size_t key, const Value& value) { values[offsets[key]++] = value; });
  group_by_key::CursorsToRowStarts(offsets, keys);
}

/// GroupByKey for items 0 .. items - 1: item i goes to row key(i) (none where key(i) is
/// negative) as value(i), rows filled in item order. From `parallelItems` items up, each thread
/// counts and fills the rows of one range of keys, reading every item: the scattered writes,
/// which take the time, are shared out, and each row is still filled in item order by one
/// thread, so the rows are the same for any thread count. (Below, one pass costs less than
/// starting threads.)
template <typename Offset, typename Value, typename KeyOf, typename ValueOf>
void GroupItemsByKey(std::size_t keys, std::int64_t items, KeyOf&& key, ValueOf&& value,
  std::vector<Offset>& offsets, std::vector<Value>& values,
  std::int64_t parallelItems = 3 * 65536)
{
  constexpr std::int64_t maximumRanges = 8;
  const std::int64_t ranges = items < parallelItems
    ? 1
    : std::max<std::int64_t>(
        1, std::min<std::int64_t>(maximumRanges, vtkSMPTools::GetEstimatedNumberOfThreads()));
  const auto forEachInRange = [&](std::int64_t range, auto&& f) {
    const auto low = static_cast<std::int64_t>(keys) * range / ranges;
    const auto high = static_cast<std::int64_t>(keys) * (range + 1) / ranges;
    for (std::int64_t i = 0; i < items; ++i)
    {
      const auto k = static_cast<std::int64_t>(key(i));
      if (k >= low && k < high)
      {
        f(static_cast<std::size_t>(k), i);
      }
    }
  };
  const auto inEachRange = [&](auto&& f) {
    vtkSMPTools::For(0, ranges, 1, [&](std::int64_t begin, std::int64_t end) {
      for (std::int64_t range = begin; range < end; ++range)
      {
        forEachInRange(range, f);
      }
    });
  };
  AssignFresh(offsets, keys + 1, Offset(0));
  inEachRange([&](std::size_t k, std::int64_t) { ++offsets[k + 1]; });
  group_by_key::CountsToRowStarts(offsets, keys);
  ResizeFresh(values, static_cast<std::size_t>(offsets[keys]));
  inEachRange([&](std::size_t k, std::int64_t i) { values[offsets[k]++] = value(i); });
  group_by_key::CursorsToRowStarts(offsets, keys);
}
} // namespace meshlod

#endif
