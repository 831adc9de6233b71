// MeshLOD core: level 0 and where each of its points has gone, for the passes that look at a
// new level through the input (LevelCentering, LevelEdgeFlips): its point in the last level
// made, found by chaining each level's MorphTargetId map (Target) onto the one before. The
// filter keeps one, advances it once per level and hands it to every such pass (with both
// CenterOnInput and FlipEdges on, each pass kept its own copy of the same map before).
#ifndef meshlod_LevelZeroCorrespondence_h
#define meshlod_LevelZeroCorrespondence_h

#include "LevelZeroView.h"
#include "TriangleMesh.h"

#include "vtkSMPTools.h"

#include <vector>

namespace meshlod
{
struct LevelZeroCorrespondence
{
  /// Level 0, read in place (what it points to must outlive this object).
  LevelZeroView Input;
  /// Per level-0 point, its point of the last level (InvalidId: none).
  std::vector<Id> LevelPoint;

  /// Level 0 itself: every point is its own.
  void Reset(const LevelZeroView& input)
  {
    this->Input = input;
    const Id points = input.Points;
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
