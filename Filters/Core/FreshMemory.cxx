#include "FreshMemory.h"

#include "vtkSMPTools.h"

#include <cstdint>

#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#ifndef MADV_POPULATE_WRITE
#define MADV_POPULATE_WRITE 23 // Linux 5.14; older kernels answer EINVAL, which is ignored
#endif
#endif

namespace meshlod
{
namespace
{
// Pages per task of the parallel first write (a task then takes some 250 us).
constexpr vtkIdType TouchGrainPages = 64;
}

//------------------------------------------------------------------------------
void PrepareForWriting(void* data, std::size_t bytes)
{
#if defined(__linux__)
  if (bytes < FreshMemoryMinimumBytes)
  {
    return;
  }
  // The whole pages inside the range (a partial page at either end is shared with other data).
  const long page = sysconf(_SC_PAGESIZE);
  if (page <= 0)
  {
    return;
  }
  const std::uintptr_t mask = static_cast<std::uintptr_t>(page) - 1;
  const std::uintptr_t begin = reinterpret_cast<std::uintptr_t>(data);
  const std::uintptr_t first = (begin + mask) & ~mask;
  const std::uintptr_t last = (begin + bytes) & ~mask;
  if (last > first)
  {
    // Maps the pages that are not mapped yet and leaves the others, and their contents, alone.
    if (madvise(reinterpret_cast<void*>(first), last - first, MADV_POPULATE_WRITE) != 0)
    {
      return; // not mapped: the caller's first writes fault as they would have
    }
    // On a virtual machine the first write to each mapped page costs again (about 4 us per page
    // on the benchmark machine, most of what remains): one byte of every page is rewritten with
    // its own value, in parallel, so that the caller's fill, often serial, finds the pages
    // ready. (Two threads halve that cost; the fill alone writes at memory speed.)
    const std::uintptr_t pageSize = static_cast<std::uintptr_t>(page);
    const vtkIdType pages = static_cast<vtkIdType>((last - first) / pageSize);
    vtkSMPTools::For(0, pages, TouchGrainPages, [first, pageSize](vtkIdType begin, vtkIdType end) {
      for (vtkIdType i = begin; i < end; ++i)
      {
        volatile unsigned char* byte = reinterpret_cast<unsigned char*>(first + i * pageSize);
        *byte = *byte;
      }
    });
  }
#else
  (void)data;
  (void)bytes;
#endif
}
} // namespace meshlod
