#include "LevelEdgeFlips.h"

#include "FreshMemory.h"
#include "GroupByKey.h"
#include "TriangulationFlips.h"
#include "Vector3.h"

#include "vtkSMPTools.h"

#include <limits>

namespace meshlod
{
//------------------------------------------------------------------------------
void LevelEdgeFlips::SetLevelZero(const LevelZeroCorrespondence& levelZero)
{
  this->LevelZero = &levelZero;
  levelZero.Input.BuildAdjacency(this->InputTriangles);
}

//------------------------------------------------------------------------------
Id LevelEdgeFlips::Apply(TriangleMesh& level, double estimatedError, std::vector<Id>* flipped)
{
  const LevelZeroView& input = this->LevelZero->Input;
  if (level.GetNumberOfTriangles() > LargestFraction * input.Triangles)
  {
    return 0;
  }

  // Each level point's walks start at the nearest input point it stands for (rows in input
  // order, so the first of equally near ones, whatever the thread count).
  const Id points = level.GetNumberOfPoints();
  const Id inputPoints = input.Points;
  std::vector<Id> offsets, members;
  GroupItemsByKey(
    static_cast<std::size_t>(points), inputPoints,
    [&](std::int64_t i) { return (*this->LevelZero)[static_cast<Id>(i)]; },
    [](std::int64_t i) { return static_cast<Id>(i); }, offsets, members);
  std::vector<Id> start = FreshVector<Id>(points, InvalidId);
  vtkSMPTools::For(0, points, [&](Id begin, Id end) {
    for (Id p = begin; p < end; ++p)
    {
      double nearest = std::numeric_limits<double>::infinity();
      for (Id k = offsets[p]; k < offsets[p + 1]; ++k)
      {
        double x[3];
        input.Point(members[k], x);
        const double d = Distance2(x, level.Point(p));
        if (d < nearest)
        {
          nearest = d;
          start[p] = members[k];
        }
      }
    }
  });
  TriangulationFlipOptions options;
  options.MaximumSweeps = 1;
  options.MinimumOppositeAngles = MinimumOppositeAngles;
  options.MinimumSeparation = MinimumSeparation;
  return ImproveTriangulation(
    input, this->InputTriangles, start, ErrorScale * estimatedError, level, options, flipped);
}
} // namespace meshlod
