// One level of detail as the algorithms hand it to the output builder (MeshLODHierarchy.h):
// plain arrays, no VTK types.
#ifndef meshlod_LevelData_h
#define meshlod_LevelData_h

#include "TriangleMesh.h"
#include "vtkFiltersMeshLODModule.h"

#include <vector>

namespace meshlod
{
/// How the points of a new level derive from the points of the level before it: for new point
/// p, Parents[Offsets[p] .. Offsets[p+1]) with the matching Weights (summing to 1). Used to
/// interpolate point data.
struct VTKFILTERSMESHLOD_EXPORT PointSources
{
  std::vector<Id> Offsets;
  std::vector<Id> Parents;
  std::vector<float> Weights;

  void Clear()
  {
    this->Offsets.assign(1, 0);
    this->Parents.clear();
    this->Weights.clear();
  }
  void Add(const Id* parents, const float* weights, int count)
  {
    this->Parents.insert(this->Parents.end(), parents, parents + count);
    this->Weights.insert(this->Weights.end(), weights, weights + count);
    this->Offsets.push_back(static_cast<Id>(this->Parents.size()));
  }
};

/// One new level, as the algorithm hands it over.
struct VTKFILTERSMESHLOD_EXPORT LevelData
{
  TriangleMesh Mesh;              // compact: every point used
  PointSources Sources;           // one entry per point of Mesh, parents in the previous level
  std::vector<Id> LevelZeroTriangle; // triangle -> the level-0 triangle it descends from
  std::vector<Id> Target;         // previous level's point -> point of Mesh (MorphTargetId)
  std::vector<Id> Rank;           // previous level's point -> CollapseRank (-1: does not move)
  double EstimatedError = 0.0;
};

} // namespace meshlod

#endif
