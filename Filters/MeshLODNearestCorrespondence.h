// Correspondence between two LOD models that share no morph data, by nearest vertices (Pan,
// Zhou, Shi, "A New Mesh Simplification Algorithm Based on Triangle Collapses", section 4,
// steps 1 and 2; the same method is in Zhou, Zhang, Shi, Pan, section 5). Used by
// vtkLODGeomorph.
#ifndef MeshLODNearestCorrespondence_h
#define MeshLODNearestCorrespondence_h

#include "Core/TriangleMesh.h"
#include "vtkFiltersMeshLODModule.h"

#include <functional>
#include <vector>

class vtkPoints;

namespace meshlod
{
/// For every point of `fine`, its partner point in `coarse`:
/// 1. every coarse point takes its nearest fine point (among equally near ones, the locator's
///    choice). When several coarse points pick the same fine point, the nearest keeps it (the
///    lowest id on ties) and the others, in increasing id, take their nearest fine point not
///    taken yet (the lowest id among equally near ones), so that every coarse point is reached
///    at t = 1 whenever the fine model has at least as many points (the paper leaves such
///    conflicts open);
/// 2. every fine point left without a partner takes its nearest coarse point.
/// Nearest-point queries run on vtkStaticPointLocator, in parallel. A coarse point that lost its
/// pick asks the locator for its 16 nearest fine points; when none of them is free, a k-d tree
/// of the free fine points (built once) answers it and the rest: most of the time those are
/// near, but levels far apart (every pick lost to a few fine points) take longer, about 3 s for
/// 100,000 and 75,000 points. The result does not depend on the number of threads.
/// `stop` (optional) is asked every 1,024 coarse points of step 1's second part: when it says
/// yes, the function returns false at once and `partner` is incomplete (levels far apart take
/// seconds there; an abort must not wait for them). Returns true when complete.
VTKFILTERSMESHLOD_EXPORT bool NearestVertexCorrespondence(vtkPoints* fine, vtkPoints* coarse,
  std::vector<Id>& partner, const std::function<bool()>& stop = nullptr);

} // namespace meshlod

#endif
