// GroupByKey (the stable counting sort into compressed rows shared by the octree, the collapse
// schedule and the level centring): exact rows on a hand-made list, empty rows and lists,
// vectors that held something before, and a large random list (on prepared memory) against a
// stable sort by key.
#include "Core/GroupByKey.h"
#include "Core/TriangleMesh.h"
#include "MeshLODTestCheck.h"

#include <algorithm>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

namespace
{
using meshlod::GroupByKey;
using meshlod::Id;

// Groups (key, value) pairs listed in `items`.
template <typename Value>
void Group(std::size_t keys, const std::vector<std::pair<Id, Value>>& items,
  std::vector<Id>& offsets, std::vector<Value>& values)
{
  GroupByKey(
    keys,
    [&](auto&& emit) {
      for (const auto& item : items)
      {
        emit(item.first, item.second);
      }
    },
    offsets, values);
}

void CheckHandMade()
{
  // Keys 2 0 2 1 0 2 (key 3 has no item): rows in listing order.
  const std::vector<std::pair<Id, Id>> items = { { 2, 10 }, { 0, 11 }, { 2, 12 }, { 1, 13 },
    { 0, 14 }, { 2, 15 } };
  std::vector<Id> offsets = { 7, 7 }, values = { 1, 2, 3, 4, 5, 6, 7, 8, 9 }; // overwritten
  Group(4, items, offsets, values);
  MESHLOD_CHECK(offsets == (std::vector<Id>{ 0, 2, 3, 6, 6 }));
  MESHLOD_CHECK(values == (std::vector<Id>{ 11, 14, 13, 10, 12, 15 }));

  // No items: every row empty. No keys and no items: one offset.
  Group(3, std::vector<std::pair<Id, Id>>{}, offsets, values);
  MESHLOD_CHECK(offsets == (std::vector<Id>{ 0, 0, 0, 0 }));
  MESHLOD_CHECK(values.empty());
  Group(0, std::vector<std::pair<Id, Id>>{}, offsets, values);
  MESHLOD_CHECK(offsets == (std::vector<Id>{ 0 }));
  MESHLOD_CHECK(values.empty());
}

void CheckRandom()
{
  // 300,000 items over 50,000 keys (2.4 MB of values: on prepared memory), values 64-bit.
  std::mt19937 random(5);
  const std::size_t keys = 50000;
  std::vector<std::pair<Id, std::uint64_t>> items(300000);
  for (std::size_t i = 0; i < items.size(); ++i)
  {
    items[i] = { static_cast<Id>(random() % keys), (std::uint64_t(random()) << 32) | i };
  }
  std::vector<Id> offsets;
  std::vector<std::uint64_t> values;
  Group(keys, items, offsets, values);
  std::vector<std::pair<Id, std::uint64_t>> sorted = items;
  std::stable_sort(sorted.begin(), sorted.end(),
    [](const auto& a, const auto& b) { return a.first < b.first; });
  MESHLOD_CHECK_EQ(offsets.size(), keys + 1);
  MESHLOD_CHECK_EQ(offsets.back(), static_cast<Id>(items.size()));
  MESHLOD_CHECK_EQ(values.size(), items.size());
  bool rowsMatch = true;
  for (std::size_t k = 0; k < keys && rowsMatch; ++k)
  {
    rowsMatch = offsets[k] <= offsets[k + 1];
    for (Id x = offsets[k]; x < offsets[k + 1] && rowsMatch; ++x)
    {
      rowsMatch = sorted[x].first == static_cast<Id>(k) && sorted[x].second == values[x];
    }
  }
  MESHLOD_CHECK(rowsMatch);

  // GroupItemsByKey on the same items (300,000: by ranges of keys in parallel), every third
  // left out by a negative key: the rows GroupByKey gives for the others.
  auto keyOf = [&](std::int64_t i) { return i % 3 == 2 ? Id(-1) : items[i].first; };
  auto valueOf = [&](std::int64_t i) { return items[i].second; };
  std::vector<Id> rangeOffsets = { 3 };
  std::vector<std::uint64_t> rangeValues = { 1, 2 };
  meshlod::GroupItemsByKey(keys, static_cast<std::int64_t>(items.size()), keyOf, valueOf,
    rangeOffsets, rangeValues);
  std::vector<std::pair<Id, std::uint64_t>> kept;
  for (std::size_t i = 0; i < items.size(); ++i)
  {
    if (i % 3 != 2)
    {
      kept.push_back(items[i]);
    }
  }
  Group(keys, kept, offsets, values);
  MESHLOD_CHECK(rangeOffsets == offsets);
  MESHLOD_CHECK(rangeValues == values);
}
} // namespace

int TestGroupByKey(int, char*[])
{
  CheckHandMade();
  CheckRandom();
  return meshlod::testing::Result();
}
