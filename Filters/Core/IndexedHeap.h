// A binary min-heap of ids keyed by an external cost array, with the position of every id kept
// so that an id's cost can be changed or the id removed in O(log n). Equal costs are ordered by
// a second key (optional), then by a fixed bijective scramble of the id, so the order (and
// everything built on it) is deterministic. Not by the id itself: on an exactly flat region
// every collapse costs 0, and taking the lowest id first would keep collapsing around the same
// survivor (its triangles keep the lowest ids), growing one vertex of huge valence. Each heap
// entry carries a copy of its
// cost: sifting then compares neighbouring entries instead of reading the cost array at random
// places, which on large meshes is most of the heap's time (cache misses).
#ifndef meshlod_IndexedHeap_h
#define meshlod_IndexedHeap_h

#include "TriangleMesh.h"

#include <cstdint>
#include <vector>

namespace meshlod
{
class IndexedHeap
{
public:
  /// Leaves the shared positions as it found them (see Attach). (Copyable for vtkSMPThreadLocal,
  /// which copies an empty exemplar: a copy of a heap holding ids would share its positions.)
  ~IndexedHeap() { this->Clear(); }

  /// Ids 0..costs->size()-1 keyed by costs[id], then ties[id] (when given); the heap reads both
  /// arrays when an id is inserted or updated (it does not copy them). The position of each id
  /// is kept in `positions` (one per id, InvalidId for every id not in this heap; the caller
  /// owns it): several heaps holding disjoint ids can share it, each used by one thread, and one
  /// array serves the heaps that come one after the other. Clear() and the destructor set the
  /// positions of the ids left in the heap back to InvalidId.
  void Attach(const std::vector<double>* costs, const std::vector<float>* ties, Id* positions)
  {
    this->Clear();
    this->Costs = costs;
    this->Ties = ties;
    this->Position = positions;
    this->Size = static_cast<Id>(costs->size());
  }

  bool Empty() const { return this->Heap.empty(); }
  std::size_t GetSize() const { return this->Heap.size(); }
  bool Contains(Id id) const { return this->Position[id] != InvalidId; }
  Id Top() const { return this->Heap.front().Item; }
  /// The id at position i of the heap's array (i < GetSize()): positions 1 and 2 hold the two
  /// candidates for the top after the next Pop.
  Id At(std::size_t i) const { return this->Heap[i].Item; }

  /// Add all ids for which keep(id) is true, then heapify in O(n).
  template <typename Keep>
  void Build(Keep&& keep)
  {
    this->Heap.clear();
    for (Id id = 0; id < this->Size; ++id)
    {
      this->Position[id] = InvalidId;
      if (keep(id))
      {
        this->Position[id] = static_cast<Id>(this->Heap.size());
        this->Heap.push_back(MakeEntry(id));
      }
    }
    this->Heapify();
  }

  /// Add `count` ids not in the heap yet, then heapify.
  void Build(const Id* ids, std::size_t count)
  {
    for (std::size_t i = 0; i < count; ++i)
    {
      this->Position[ids[i]] = static_cast<Id>(this->Heap.size());
      this->Heap.push_back(MakeEntry(ids[i]));
    }
    this->Heapify();
  }

  /// Remove every id.
  void Clear()
  {
    for (const Entry& entry : this->Heap)
    {
      this->Position[entry.Item] = InvalidId;
    }
    this->Heap.clear();
  }

  Id Pop()
  {
    const Id top = this->Heap.front().Item;
    this->Remove(top);
    return top;
  }

  void Remove(Id id)
  {
    const Id i = this->Position[id];
    if (i == InvalidId)
    {
      return;
    }
    const Entry last = this->Heap.back();
    this->Heap.pop_back();
    this->Position[id] = InvalidId;
    if (last.Item != id)
    {
      this->Heap[i] = last;
      this->Position[last.Item] = i;
      this->SiftDown(this->SiftUp(i));
    }
  }

  /// Insert the id, or restore the heap order after its cost changed.
  void Update(Id id)
  {
    Id i = this->Position[id];
    if (i == InvalidId)
    {
      i = static_cast<Id>(this->Heap.size());
      this->Heap.push_back(MakeEntry(id));
      this->Position[id] = i;
    }
    else
    {
      this->Heap[i] = this->MakeEntry(id);
    }
    this->SiftDown(this->SiftUp(i));
  }

private:
  struct Entry
  {
    double Cost;
    float Tie;
    Id Item;
  };

  // A bijection of 32-bit integers that mixes every bit into every other (the finaliser of
  // MurmurHash3): each step is invertible.
  static std::uint32_t Scramble(Id id)
  {
    std::uint32_t h = static_cast<std::uint32_t>(id);
    h ^= h >> 16;
    h *= 0x85ebca6bu;
    h ^= h >> 13;
    h *= 0xc2b2ae35u;
    h ^= h >> 16;
    return h;
  }

  Entry MakeEntry(Id id) const
  {
    return { (*this->Costs)[id], this->Ties ? (*this->Ties)[id] : 0.0f, id };
  }

  static bool Less(const Entry& a, const Entry& b)
  {
    return a.Cost < b.Cost ||
      (a.Cost == b.Cost &&
        (a.Tie < b.Tie || (a.Tie == b.Tie && Scramble(a.Item) < Scramble(b.Item))));
  }

  void Heapify()
  {
    for (Id i = static_cast<Id>(this->Heap.size()) / 2 - 1; i >= 0; --i)
    {
      this->SiftDown(i);
    }
  }

  Id SiftUp(Id i)
  {
    const Entry entry = this->Heap[i];
    while (i > 0)
    {
      const Id parent = (i - 1) / 2;
      if (!Less(entry, this->Heap[parent]))
      {
        break;
      }
      this->Heap[i] = this->Heap[parent];
      this->Position[this->Heap[i].Item] = i;
      i = parent;
    }
    this->Heap[i] = entry;
    this->Position[entry.Item] = i;
    return i;
  }

  void SiftDown(Id i)
  {
    const Id size = static_cast<Id>(this->Heap.size());
    const Entry entry = this->Heap[i];
    for (;;)
    {
      Id child = 2 * i + 1;
      if (child >= size)
      {
        break;
      }
      if (child + 1 < size && Less(this->Heap[child + 1], this->Heap[child]))
      {
        ++child;
      }
      if (!Less(this->Heap[child], entry))
      {
        break;
      }
      this->Heap[i] = this->Heap[child];
      this->Position[this->Heap[i].Item] = i;
      i = child;
    }
    this->Heap[i] = entry;
    this->Position[entry.Item] = i;
  }

  const std::vector<double>* Costs = nullptr;
  const std::vector<float>* Ties = nullptr;
  std::vector<Entry> Heap;
  Id* Position = nullptr; // the caller's (Attach)
  Id Size = 0;
};

} // namespace meshlod

#endif
