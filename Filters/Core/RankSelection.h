// MeshLOD core: the k-th smallest of many numbers, mostly in parallel.
//
// std::nth_element is serial and reads every number several times. Here a small sorted subset
// (every step-th number) brackets the rank: one parallel pass counts the numbers below the
// bracket and gathers those inside it, and nth_element runs on the gathered few only. The
// answer is the rank's value itself, which neither the gathering order nor the thread count
// changes; in the rare case the bracket misses the rank, the serial way gives it.
#ifndef meshlod_RankSelection_h
#define meshlod_RankSelection_h

#include "TriangleMesh.h"

#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <vector>

namespace meshlod
{
/// The value of rank `rank` (0 for the smallest) among the numbers of `values` that are not
/// NaN, of which there are `count` (rank < count): what std::nth_element gives on them.
inline double SelectRank(const std::vector<double>& values, Id count, Id rank)
{
  const Id n = static_cast<Id>(values.size());
  const auto serial = [&]() {
    std::vector<double> numbers;
    numbers.reserve(count);
    std::copy_if(values.begin(), values.end(), std::back_inserter(numbers),
      [](double x) { return !std::isnan(x); });
    std::nth_element(numbers.begin(), numbers.begin() + rank, numbers.end());
    return numbers[rank];
  };
  // About this many numbers bracket the rank (sorting them is the serial part).
  constexpr Id Splitters = 1024;
  if (count < 8 * Splitters)
  {
    return serial();
  }
  std::vector<double> splitters;
  splitters.reserve(2 * Splitters);
  const Id step = std::max<Id>(1, n / Splitters);
  for (Id i = 0; i < n; i += step)
  {
    if (!std::isnan(values[i]))
    {
      splitters.push_back(values[i]);
    }
  }
  std::sort(splitters.begin(), splitters.end());
  // Where the rank falls among the splitters, give or take four standard deviations of that
  // estimate (a binomial proportion over the splitters) and two places.
  const double s = static_cast<double>(splitters.size());
  const double p = (static_cast<double>(rank) + 0.5) / static_cast<double>(count);
  const double margin = 4.0 * std::sqrt(s * p * (1.0 - p)) + 2.0;
  const double low = std::floor(p * s - margin), high = std::ceil(p * s + margin);
  const double lower = low < 0.0 ? -HUGE_VAL : splitters[static_cast<std::size_t>(low)];
  const double upper = high >= s ? HUGE_VAL : splitters[static_cast<std::size_t>(high)];

  vtkSMPThreadLocal<Id> below(0);
  vtkSMPThreadLocal<std::vector<double>> inside;
  vtkSMPTools::For(0, n, [&](Id begin, Id end) {
    Id& under = below.Local();
    std::vector<double>& gathered = inside.Local();
    for (Id i = begin; i < end; ++i)
    {
      const double x = values[i]; // NaN fails both tests
      under += x < lower ? 1 : 0;
      if (x >= lower && x <= upper)
      {
        gathered.push_back(x);
      }
    }
  });
  Id under = 0;
  for (const Id b : below)
  {
    under += b;
  }
  std::vector<double> window;
  for (const std::vector<double>& gathered : inside)
  {
    window.insert(window.end(), gathered.begin(), gathered.end());
  }
  const Id within = rank - under;
  if (within < 0 || within >= static_cast<Id>(window.size()))
  {
    return serial();
  }
  std::nth_element(window.begin(), window.begin() + within, window.end());
  return window[within];
}

} // namespace meshlod

#endif
