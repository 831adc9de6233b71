// A binary min-heap of ids keyed by an external cost array, with the position of every id kept
// so that an id's cost can be changed or the id removed in O(log n). Ties are broken by id, so
// the order (and everything built on it) is deterministic. Each heap entry carries a copy of its
// cost: sifting then compares neighbouring entries instead of reading the cost array at random
// places, which on large meshes is most of the heap's time (cache misses).
#ifndef meshlod_IndexedHeap_h
#define meshlod_IndexedHeap_h

#include "TriangleMesh.h"

#include <vector>

namespace meshlod
{
class IndexedHeap
{
public:
  /// Ids 0..size-1 keyed by costs[id]; the heap reads `costs` (it does not copy it).
  void Reset(const std::vector<double>* costs, Id size)
  {
    this->Costs = costs;
    this->Heap.clear();
    this->Position.assign(size, InvalidId);
  }

  bool Empty() const { return this->Heap.empty(); }
  bool Contains(Id id) const { return this->Position[id] != InvalidId; }
  Id Top() const { return this->Heap.front().Item; }

  /// Add all ids for which keep(id) is true, then heapify in O(n).
  template <typename Keep>
  void Build(Keep&& keep)
  {
    this->Heap.clear();
    for (Id id = 0; id < static_cast<Id>(this->Position.size()); ++id)
    {
      this->Position[id] = InvalidId;
      if (keep(id))
      {
        this->Position[id] = static_cast<Id>(this->Heap.size());
        this->Heap.push_back({ (*this->Costs)[id], id });
      }
    }
    for (Id i = static_cast<Id>(this->Heap.size()) / 2 - 1; i >= 0; --i)
    {
      this->SiftDown(i);
    }
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
      this->Heap.push_back({ (*this->Costs)[id], id });
      this->Position[id] = i;
    }
    else
    {
      this->Heap[i].Cost = (*this->Costs)[id];
    }
    this->SiftDown(this->SiftUp(i));
  }

private:
  struct Entry
  {
    double Cost;
    Id Item;
  };

  static bool Less(const Entry& a, const Entry& b)
  {
    return a.Cost < b.Cost || (a.Cost == b.Cost && a.Item < b.Item);
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
  std::vector<Entry> Heap;
  std::vector<Id> Position;
};

} // namespace meshlod

#endif
