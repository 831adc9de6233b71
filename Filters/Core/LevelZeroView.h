// MeshLOD core: level 0 (the validated input) read where it already is, for the passes that
// look at a new level through the input (LevelCentering, TriangulationFlips through
// LevelEdgeFlips and vtkVertexClusterOctree). vtkTriangleCollapseDecimation's engine takes its
// TriangleMesh over and collapses it, so these read the hierarchy's level-0 vtkPolyData in
// place (HierarchyBuilder::GetLevelZeroView) instead of keeping a copy: 24 bytes per input
// triangle less (double points, 32-bit ids) for its FlipEdges, and the points of a single
// precision input stay in single precision. The octree keeps its input mesh, and its flips
// view that through Of().
#ifndef meshlod_LevelZeroView_h
#define meshlod_LevelZeroView_h

#include "GroupByKey.h"
#include "TriangleMesh.h"

#include "vtkType.h"

#include <cstddef>

namespace meshlod
{
/// Points in double or single precision (one of the two pointers set), triangles as three 32-
/// or 64-bit point ids each (one of the two set), every point used by a triangle. Reads only:
/// what it points to must outlive it.
struct LevelZeroView
{
  const double* Doubles = nullptr;
  const float* Floats = nullptr;
  const vtkTypeInt32* Ids32 = nullptr;
  const vtkTypeInt64* Ids64 = nullptr;
  Id Points = 0;
  Id Triangles = 0;

  /// A mesh held as a TriangleMesh (not copied).
  static LevelZeroView Of(const TriangleMesh& mesh)
  {
    static_assert(sizeof(Id) == sizeof(vtkTypeInt32), "TriangleMesh ids are 32-bit");
    LevelZeroView view;
    view.Doubles = mesh.Points.data();
    view.Ids32 = mesh.Triangles.data();
    view.Points = mesh.GetNumberOfPoints();
    view.Triangles = mesh.GetNumberOfTriangles();
    return view;
  }

  /// Corner k (0, 1, 2) of triangle t.
  Id Corner(Id t, int k) const
  {
    const std::size_t i = 3 * static_cast<std::size_t>(t) + k;
    return static_cast<Id>(this->Ids32 ? this->Ids32[i] : this->Ids64[i]);
  }

  /// Point v in double precision.
  void Point(Id v, double x[3]) const
  {
    const std::size_t i = 3 * static_cast<std::size_t>(v);
    for (int k = 0; k < 3; ++k)
    {
      x[k] = this->Doubles ? this->Doubles[i + k] : static_cast<double>(this->Floats[i + k]);
    }
  }

  /// Calls f with the view's arrays as a TypedLevelZeroView<point type, id type> (below): the
  /// same Point and Corner, with no test of the storage per read, for hot loops.
  template <typename F>
  void Dispatch(F&& f) const;

  /// The triangles around each point (VertexTriangleAdjacency::Build's rows; every triangle
  /// counts, a view has no deleted ones).
  void BuildAdjacency(VertexTriangleAdjacency& adjacency) const
  {
    GroupItemsByKey(
      static_cast<std::size_t>(this->Points), 3 * static_cast<std::int64_t>(this->Triangles),
      [this](std::int64_t k) { return this->Corner(static_cast<Id>(k / 3), k % 3); },
      [](std::int64_t k) { return static_cast<Id>(k / 3); }, adjacency.Offsets,
      adjacency.Triangles);
  }
};

template <typename PointType, typename IdType>
struct TypedLevelZeroView
{
  const PointType* Points;
  const IdType* Ids;

  Id Corner(Id t, int k) const
  {
    return static_cast<Id>(this->Ids[3 * static_cast<std::size_t>(t) + k]);
  }
  void Point(Id v, double x[3]) const
  {
    const PointType* p = this->Points + 3 * static_cast<std::size_t>(v);
    x[0] = static_cast<double>(p[0]);
    x[1] = static_cast<double>(p[1]);
    x[2] = static_cast<double>(p[2]);
  }
};

template <typename F>
void LevelZeroView::Dispatch(F&& f) const
{
  if (this->Doubles)
  {
    this->Ids32 ? f(TypedLevelZeroView<double, vtkTypeInt32>{ this->Doubles, this->Ids32 })
                : f(TypedLevelZeroView<double, vtkTypeInt64>{ this->Doubles, this->Ids64 });
  }
  else
  {
    this->Ids32 ? f(TypedLevelZeroView<float, vtkTypeInt32>{ this->Floats, this->Ids32 })
                : f(TypedLevelZeroView<float, vtkTypeInt64>{ this->Floats, this->Ids64 });
  }
}
} // namespace meshlod

#endif
