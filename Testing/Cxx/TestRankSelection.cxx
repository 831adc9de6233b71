// SelectRank (the partitioned greedy schedule's cost threshold) against std::nth_element: the
// same value for every rank tried, with NaNs to skip, many equal values, a subset that
// misjudges the rank (the serial fallback) and too few numbers for the bracket.
#include "Core/RankSelection.h"
#include "MeshLODTestCheck.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace
{
using namespace meshlod;

double Expected(const std::vector<double>& values, Id rank)
{
  std::vector<double> numbers;
  for (const double x : values)
  {
    if (!std::isnan(x))
    {
      numbers.push_back(x);
    }
  }
  std::nth_element(numbers.begin(), numbers.begin() + rank, numbers.end());
  return numbers[rank];
}

Id Count(const std::vector<double>& values)
{
  return static_cast<Id>(
    std::count_if(values.begin(), values.end(), [](double x) { return !std::isnan(x); }));
}

// Every rank in `ranks` (fractions of the count) and a few random ones.
void CheckRanks(const std::vector<double>& values, std::mt19937& random)
{
  const Id count = Count(values);
  std::vector<Id> ranks = { 0, 1, count / 3, count / 2, count - 2, count - 1 };
  std::uniform_int_distribution<Id> any(0, count - 1);
  for (int i = 0; i < 10; ++i)
  {
    ranks.push_back(any(random));
  }
  for (const Id rank : ranks)
  {
    MESHLOD_CHECK_EQ(SelectRank(values, count, rank), Expected(values, rank));
  }
}
} // namespace

int TestRankSelection(int, char*[])
{
  std::mt19937 random(12345);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();

  // Costs in the way CostQuantile samples them: a fifth NaN (dead or parked triangles).
  std::vector<double> values(100000);
  for (double& x : values)
  {
    x = uniform(random) < 0.2 ? nan : std::pow(uniform(random), 4.0);
  }
  CheckRanks(values, random);

  // Half the costs exactly zero (flat parts), the rest in three values: the bracket's ends
  // coincide with many numbers.
  for (double& x : values)
  {
    const double u = uniform(random);
    x = u < 0.5 ? 0.0 : (u < 0.7 ? 1.0 : (u < 0.9 ? 2.0 : 3.0));
  }
  CheckRanks(values, random);

  // Every number the subset takes (each step-th one, step = 100000 / 1024 = 97) far above the
  // rest: the bracket misses most ranks, and the serial way answers.
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    values[i] = i % 97 == 0 ? 1e9 + static_cast<double>(i) : uniform(random);
  }
  CheckRanks(values, random);

  // Too few numbers to bracket.
  values.resize(5000);
  CheckRanks(values, random);
  return meshlod::testing::Result();
}
