// MeshLOD core: large arrays on memory mapped for them in one go.
//
// The first write to each page of memory that is new to the process costs a page fault. On a
// virtual machine a fault costs several microseconds (about 10 us per 4 KB page measured on the
// benchmark machine), so filling a fresh 100 MB array spends far more time in faults than in
// writing: for the triangle collapse's working arrays, about a fifth of a whole run. Before the
// first write, PrepareForWriting asks the kernel to map the range in one call instead of a fault
// per page (MADV_POPULATE_WRITE, Linux 5.14 and later: about half the cost per page). It is a
// hint: where the kernel does not have it, the first writes fault as before. On a virtual
// machine the first write to each mapped page still costs (about 4 us per page there), so one
// byte of every page is then rewritten with its own value, with vtkSMPTools: with two threads
// that half of the cost takes half the time, where the caller's fill is often serial. Contents
// do not change, and nor does the memory used: only ranges that are then written in full are
// prepared.
// (Asking for transparent huge pages as well gained nothing more on the benchmark meshes and
// would leave its mark on the caller's heap, so it is not done.)
#ifndef meshlod_FreshMemory_h
#define meshlod_FreshMemory_h

#include <algorithm>
#include <cstddef>
#include <iterator>
#include <vector>

namespace meshlod
{
/// Ranges below this are left alone (the allocator serves them from memory it often has
/// mapped already).
constexpr std::size_t FreshMemoryMinimumBytes = 256 * 1024;

/// Prepare [data, data + bytes), memory the caller is about to write in full.
void PrepareForWriting(void* data, std::size_t bytes);

/// Make room in v for n elements, on prepared memory when the room is new and large; the
/// elements v holds are kept. Call before the assign() or resize() that fills all n. A vector
/// that grows again gets twice its room, as std::vector would (only n elements are prepared).
template <typename T>
void ReserveFresh(std::vector<T>& v, std::size_t n)
{
  if (v.capacity() >= n || n * sizeof(T) < FreshMemoryMinimumBytes)
  {
    return;
  }
  std::vector<T> fresh;
  fresh.reserve(v.capacity() > 0 ? std::max(n, 2 * v.capacity()) : n);
  PrepareForWriting(fresh.data(), n * sizeof(T));
  fresh.insert(fresh.end(), std::make_move_iterator(v.begin()), std::make_move_iterator(v.end()));
  v.swap(fresh);
}

/// v.resize(n) or v.resize(n, value), on prepared memory when the room is new and large.
template <typename T, typename... Value>
void ResizeFresh(std::vector<T>& v, std::size_t n, const Value&... value)
{
  ReserveFresh(v, n);
  v.resize(n, value...);
}

/// v.assign(n, value), on prepared memory when the room is new and large.
template <typename T>
void AssignFresh(
  std::vector<T>& v, std::size_t n, const typename std::vector<T>::value_type& value)
{
  ReserveFresh(v, n);
  v.assign(n, value);
}

/// A vector of n copies of value, on prepared memory when it is large.
template <typename T>
std::vector<T> FreshVector(std::size_t n, const T& value = T())
{
  std::vector<T> v;
  AssignFresh(v, n, value);
  return v;
}

/// A vector holding [first, last), on prepared memory when it is large.
template <typename Iterator>
auto FreshCopy(Iterator first, Iterator last)
  -> std::vector<typename std::iterator_traits<Iterator>::value_type>
{
  std::vector<typename std::iterator_traits<Iterator>::value_type> v;
  ReserveFresh(v, static_cast<std::size_t>(std::distance(first, last)));
  v.assign(first, last);
  return v;
}

/// Give v's memory back now (clear() keeps it).
template <typename T>
void Release(std::vector<T>& v)
{
  std::vector<T>().swap(v);
}

/// Give v's spare room back when it uses less than half of it (by a copy; shrink_to_fit may
/// keep the room).
template <typename T>
void ShrinkLoose(std::vector<T>& v)
{
  if (v.size() < v.capacity() / 2 && v.capacity() * sizeof(T) >= FreshMemoryMinimumBytes)
  {
    std::vector<T> tight = FreshCopy(v.begin(), v.end());
    v.swap(tight);
  }
}
} // namespace meshlod

#endif
