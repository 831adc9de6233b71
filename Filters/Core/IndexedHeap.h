// A binary min-heap of ids keyed by an external cost array, with the position of every id kept
// so that an id's cost can be changed or the id removed in O(log n). Ties are broken by id, so
// the order (and everything built on it) is deterministic.
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
  Id Top() const { return this->Heap.front(); }

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
        this->Heap.push_back(id);
      }
    }
    for (Id i = static_cast<Id>(this->Heap.size()) / 2 - 1; i >= 0; --i)
    {
      this->SiftDown(i);
    }
  }

  Id Pop()
  {
    const Id top = this->Heap.front();
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
    const Id last = this->Heap.back();
    this->Heap.pop_back();
    this->Position[id] = InvalidId;
    if (last != id)
    {
      this->Heap[i] = last;
      this->Position[last] = i;
      this->Update(last);
    }
  }

  /// Insert the id, or restore the heap order after its cost changed.
  void Update(Id id)
  {
    Id i = this->Position[id];
    if (i == InvalidId)
    {
      i = static_cast<Id>(this->Heap.size());
      this->Heap.push_back(id);
      this->Position[id] = i;
    }
    this->SiftDown(this->SiftUp(i));
  }

private:
  bool Less(Id a, Id b) const
  {
    const double ca = (*this->Costs)[a], cb = (*this->Costs)[b];
    return ca < cb || (ca == cb && a < b);
  }

  Id SiftUp(Id i)
  {
    const Id id = this->Heap[i];
    while (i > 0)
    {
      const Id parent = (i - 1) / 2;
      if (!this->Less(id, this->Heap[parent]))
      {
        break;
      }
      this->Heap[i] = this->Heap[parent];
      this->Position[this->Heap[i]] = i;
      i = parent;
    }
    this->Heap[i] = id;
    this->Position[id] = i;
    return i;
  }

  void SiftDown(Id i)
  {
    const Id size = static_cast<Id>(this->Heap.size());
    const Id id = this->Heap[i];
    for (;;)
    {
      Id child = 2 * i + 1;
      if (child >= size)
      {
        break;
      }
      if (child + 1 < size && this->Less(this->Heap[child + 1], this->Heap[child]))
      {
        ++child;
      }
      if (!this->Less(this->Heap[child], id))
      {
        break;
      }
      this->Heap[i] = this->Heap[child];
      this->Position[this->Heap[i]] = i;
      i = child;
    }
    this->Heap[i] = id;
    this->Position[id] = i;
  }

  const std::vector<double>* Costs = nullptr;
  std::vector<Id> Heap;
  std::vector<Id> Position;
};

} // namespace meshlod

#endif
