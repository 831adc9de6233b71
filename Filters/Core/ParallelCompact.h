// MeshLOD core: keeping the items of a range that pass a test, in order, in parallel.
#ifndef meshlod_ParallelCompact_h
#define meshlod_ParallelCompact_h

#include "FreshMemory.h"
#include "TriangleMesh.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace meshlod
{
/// [0, n) cut into fixed blocks of Size items (the last one shorter): work split this way, in
/// parallel or not, and combined block by block in order, gives the same result for any number
/// of threads.
struct FixedBlocks
{
  static constexpr Id Size = 16384;
  Id N;

  Id Count() const { return static_cast<Id>((std::int64_t(this->N) + Size - 1) / Size); }
  Id Begin(Id b) const { return b * Size; }
  Id End(Id b) const { return b * Size + std::min(Size, this->N - b * Size); }
};

/// The i in [0, n) for which keep(i) holds, numbered 0, 1, 2, ... in increasing order: counts
/// per fixed block of the range, a serial prefix sum over the blocks, then the numbering. The
/// blocks do not depend on how vtkSMPTools spreads them over threads, so neither does the
/// result. Two steps, so that the caller can size its outputs from Count() in between:
///
///   const ParallelCompaction live(n, keep);
///   out.resize(live.Count());
///   live.Write(keep, [&](Id i, Id slot) { out[slot] = i; });
class ParallelCompaction
{
public:
  template <typename Keep>
  ParallelCompaction(Id n, Keep&& keep)
    : Blocks{ n }
    , Offsets(static_cast<std::size_t>(Blocks.Count()) + 1, 0)
  {
    vtkSMPTools::For(0, this->Blocks.Count(), [&](Id begin, Id end) {
      for (Id b = begin; b < end; ++b)
      {
        Id count = 0;
        for (Id i = this->Blocks.Begin(b); i < this->Blocks.End(b); ++i)
        {
          count += keep(i) ? 1 : 0;
        }
        this->Offsets[b + 1] = count;
      }
    });
    for (Id b = 0; b < this->Blocks.Count(); ++b)
    {
      this->Offsets[b + 1] += this->Offsets[b];
    }
  }

  /// How many pass.
  Id Count() const { return this->Offsets.back(); }

  /// Call write(i, slot) for every i that passes, slot being its number; `keep` must answer as
  /// it did for the constructor.
  template <typename Keep, typename Writer>
  void Write(Keep&& keep, Writer&& write) const
  {
    vtkSMPTools::For(0, this->Blocks.Count(), [&](Id begin, Id end) {
      for (Id b = begin; b < end; ++b)
      {
        Id slot = this->Offsets[b];
        for (Id i = this->Blocks.Begin(b); i < this->Blocks.End(b); ++i)
        {
          if (keep(i))
          {
            write(i, slot++);
          }
        }
      }
    });
  }

private:
  FixedBlocks Blocks;
  std::vector<Id> Offsets; // per block, the number passing before it; the total last
};

/// Both steps at once, for outputs sized beforehand; returns how many pass.
template <typename Keep, typename Write>
Id ParallelCompact(Id n, Keep&& keep, Write&& write)
{
  const ParallelCompaction compaction(n, keep);
  compaction.Write(keep, write);
  return compaction.Count();
}

/// The ids in [0, n) that pass keep(id), in increasing order, into `ids` (on fresh memory).
template <typename Keep>
void ListPassing(Id n, Keep&& keep, std::vector<Id>& ids)
{
  const ParallelCompaction passing(n, keep);
  ResizeFresh(ids, static_cast<std::size_t>(passing.Count()));
  passing.Write(keep, [&](Id i, Id slot) { ids[slot] = i; });
}

/// Keep the ids in `ids` that pass keep(id), in order, in place (no second array, which at the
/// start of a run would raise the peak memory): each fixed block keeps its own in front of
/// itself in parallel, then the blocks' kept items move down into place one block after the
/// other (each moves to where earlier blocks have been read already).
template <typename Keep>
void KeepInOrder(std::vector<Id>& ids, Keep&& keep)
{
  const FixedBlocks blocks{ static_cast<Id>(ids.size()) };
  std::vector<Id> kept(static_cast<std::size_t>(blocks.Count()));
  vtkSMPTools::For(0, blocks.Count(), [&](Id begin, Id end) {
    for (Id b = begin; b < end; ++b)
    {
      Id* block = ids.data() + blocks.Begin(b);
      Id count = 0;
      for (Id i = 0; i < blocks.End(b) - blocks.Begin(b); ++i)
      {
        if (keep(block[i]))
        {
          block[count++] = block[i];
        }
      }
      kept[b] = count;
    }
  });
  Id size = 0;
  for (Id b = 0; b < blocks.Count(); ++b)
  {
    const Id* block = ids.data() + blocks.Begin(b);
    if (size < blocks.Begin(b)) // else already in place
    {
      std::copy(block, block + kept[b], ids.data() + size);
    }
    size += kept[b];
  }
  ids.resize(static_cast<std::size_t>(size));
}

} // namespace meshlod

#endif
