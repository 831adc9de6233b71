// MeshLOD core: a union-find forest that several threads join sets in at once (from
// vtkSMPTools passes), for the piece and fan counts of PieceGenus and the octree's pieces.
//
// Two roots are joined by linking the larger under the smaller with a compare-and-swap, which
// fails, and is tried again from the new roots, when another thread linked either first. A link
// always points to a smaller id, so each set's root is its smallest member: the sets, their
// roots and whatever is counted from them are the same in whatever order the threads join, for
// any thread count.
#ifndef meshlod_ConcurrentForest_h
#define meshlod_ConcurrentForest_h

#include "FreshMemory.h"
#include "TriangleMesh.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <memory>

namespace meshlod
{
class ConcurrentForest
{
public:
  /// Ids 0 .. size - 1, each a set of its own.
  explicit ConcurrentForest(Id size)
    : Up(new std::atomic<Id>[static_cast<std::size_t>(size)])
  {
    PrepareForWriting(this->Up.get(), static_cast<std::size_t>(size) * sizeof(std::atomic<Id>));
    vtkSMPTools::For(0, size, [this](Id begin, Id end) {
      for (Id v = begin; v < end; ++v)
      {
        this->Up[v].store(v, std::memory_order_relaxed);
      }
    });
  }

  /// The root (smallest member) of v's set as joined so far. Halves the path on the way: a
  /// link that is not a root's only ever moves up to an ancestor, whoever else writes it.
  Id Root(Id v)
  {
    Id up = this->Up[v].load(std::memory_order_acquire);
    while (up != v)
    {
      const Id upUp = this->Up[up].load(std::memory_order_acquire);
      if (upUp != up)
      {
        this->Up[v].store(upUp, std::memory_order_release);
      }
      v = up;
      up = upUp;
    }
    return v;
  }

  /// Joins the sets of a and b.
  void Join(Id a, Id b)
  {
    for (;;)
    {
      a = this->Root(a);
      b = this->Root(b);
      if (a == b)
      {
        return;
      }
      if (a < b)
      {
        std::swap(a, b);
      }
      Id expected = a; // a must still be a root
      if (this->Up[a].compare_exchange_weak(expected, b, std::memory_order_acq_rel))
      {
        return;
      }
    }
  }

  /// Whether v is the root of its set (call when no thread is joining).
  bool IsRoot(Id v) const { return this->Up[v].load(std::memory_order_relaxed) == v; }

private:
  std::unique_ptr<std::atomic<Id>[]> Up;
};
} // namespace meshlod

#endif
