// Checks on LOD hierarchies shared by the tests of both decimation filters and the geomorph:
// each returns the number of violations found (0 = the property holds) and prints the first few.
#ifndef MeshLODHierarchyChecks_h
#define MeshLODHierarchyChecks_h

#include "vtkSmartPointer.h"
#include "vtkType.h"

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <utility>
#include <vector>

class vtkDataArray;
class vtkMultiBlockDataSet;
class vtkPolyData;

namespace meshlod
{
namespace testing
{
/// Topology of one mesh: counts of non-manifold edges and vertices, boundary edges, whether
/// the orientation is consistent, the Euler characteristic, degenerate (zero-area) triangles
/// and triangles listed twice (in either orientation, and in the same orientation).
struct MeshReport
{
  std::int64_t Triangles = 0;
  std::int64_t NonManifoldEdges = 0;
  std::int64_t NonManifoldVertices = 0;
  std::int64_t BoundaryEdges = 0;
  std::int64_t DegenerateTriangles = 0;
  std::int64_t DuplicateTriangles = 0;
  std::int64_t SameOrientationDuplicates = 0;
  std::int64_t EulerCharacteristic = 0;
  bool ConsistentlyOriented = true;
};
MeshReport InspectMesh(vtkPolyData* mesh);

/// Every triangle of level i, mapped through MorphTargetId, is a triangle of level i+1 with the
/// same orientation, or degenerates; every triangle of level i+1 is such an image; MorphTarget
/// is the position of the MorphTargetId point; a point with CollapseRank -1 keeps its position
/// and is the only point mapped to its target.
std::int64_t CountCorrespondenceViolations(vtkMultiBlockDataSet* hierarchy);

/// Triangles of `coarse` whose normal points against the normal of the closest triangle of
/// `fine` (flipped triangles).
std::int64_t CountFlippedTriangles(vtkPolyData* fine, vtkPolyData* coarse);

/// Largest distance from a boundary vertex of `coarse` to the boundary edges of `fine`.
double BoundaryDeviation(vtkPolyData* fine, vtkPolyData* coarse);

/// True when the two meshes have bitwise equal points and cells.
bool SameMesh(vtkPolyData* a, vtkPolyData* b);

/// True when both arrays exist and have the same data type, shape and values.
bool SameValues(vtkDataArray* a, vtkDataArray* b);

/// Block i of a hierarchy as a polydata (null when it is not one).
vtkPolyData* Level(vtkMultiBlockDataSet* hierarchy, unsigned int i);

/// Levels that are not the same mesh (SameMesh) in both hierarchies, counting every level one
/// of them lacks.
std::int64_t CountDifferingLevels(vtkMultiBlockDataSet* a, vtkMultiBlockDataSet* b);

/// `run` (a filter with its defaults, returning its hierarchy) on an icosphere and on the same
/// icosphere with one more point, NaN and used by no triangle: the levels that differ (every
/// level, when the second run failed).
std::int64_t CountLevelsChangedByUnusedNaNPoint(
  const std::function<vtkSmartPointer<vtkMultiBlockDataSet>(vtkPolyData*)>& run);

/// The triangles of a mesh's polygons, in cell order (other polygons skipped).
using TriangleIds = std::array<vtkIdType, 3>;
std::vector<TriangleIds> Triangles(vtkPolyData* mesh);

/// Triangles of every level of `hierarchy` with a point twice, and triangles on the same three
/// points as another of their level (in any order).
std::int64_t CountRepeatedPointTriangles(vtkMultiBlockDataSet* hierarchy);

/// The number of triangles on each edge of a mesh (edge as its two point ids, smaller first).
using EdgeIds = std::pair<vtkIdType, vtkIdType>;
std::map<EdgeIds, int> EdgeTriangleCounts(vtkPolyData* mesh);

/// Runs `make` with the Sequential vtkSMPTools backend, then with the backend that was in use
/// (which is restored), and returns deep copies of both outputs: for "same output for any
/// thread count" checks.
std::pair<vtkSmartPointer<vtkPolyData>, vtkSmartPointer<vtkPolyData>> RunWithBothBackends(
  const std::function<vtkSmartPointer<vtkPolyData>()>& make);

} // namespace testing
} // namespace meshlod

#endif
