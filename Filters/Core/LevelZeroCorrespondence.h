// MeshLOD core: where each point of level 0 has gone, for the passes that look at a new level
// through the input (LevelCentering, LevelEdgeFlips): its point in the last level made, found by
// chaining each level's MorphTargetId map (Target) onto the one before.
#ifndef meshlod_LevelZeroCorrespondence_h
#define meshlod_LevelZeroCorrespondence_h

#include "TriangleMesh.h"

#include "vtkSMPTools.h"

#include <vector>

namespace meshlod
{
struct LevelZeroCorrespondence
{
  /// Per level-0 point, its point of the last level (InvalidId: none).
  std::vector<Id> LevelPoint;

  /// Level 0 itself: every point is its own.
  void Reset(Id points)
  {
    this->LevelPoint.resize(static_cast<std::size_t>(points));
    vtkSMPTools::For(0, points, [&](Id begin, Id end) {
      for (Id v = begin; v < end; ++v)
      {
        this->LevelPoint[v] = v;
      }
    });
  }

  /// One level further: `target` maps the last level's points to the new level's.
  void Advance(const std::vector<Id>& target)
  {
    vtkSMPTools::For(0, static_cast<Id>(this->LevelPoint.size()), [&](Id begin, Id end) {
      for (Id i = begin; i < end; ++i)
      {
        const Id p = this->LevelPoint[i];
        this->LevelPoint[i] = p == InvalidId ? InvalidId : target[p];
      }
    });
  }

  Id operator[](Id i) const { return this->LevelPoint[i]; }
};
} // namespace meshlod

#endif
