// Blending point arrays between two levels, for vtkLODGeomorph: output point q takes
// (1 - w) a[A] + w b[B], with A = Source[q] the point of the finer level it comes from and
// B = Map[A] the row of the coarser arrays that point goes to.
#ifndef MeshLODBlend_h
#define MeshLODBlend_h

#include "Core/TriangleMesh.h"
#include "vtkFiltersMeshLODModule.h"
#include "vtkSmartPointer.h"
#include "vtkType.h"

#include <vector>

class vtkAbstractArray;
class vtkDataArray;
class vtkPointData;

namespace meshlod
{
/// Output arrays recycled from one update to the next. An array handed out before is handed
/// out again (same value type, layout, components and size: no new allocation, its pages
/// already mapped) once nothing but the pool holds it, i.e. once the output that carried it has
/// been cleared and nobody downstream kept it. Fresh arrays of many megabytes on every frame
/// cost more in page faults than the blend itself.
class VTKFILTERSMESHLOD_EXPORT ArrayPool
{
public:
  /// An array of `like`'s class with its number of components and `tuples` tuples.
  vtkSmartPointer<vtkAbstractArray> Take(vtkAbstractArray* like, vtkIdType tuples);

private:
  std::vector<vtkSmartPointer<vtkAbstractArray>> Arrays;
};

struct BlendPlan
{
  vtkIdType NumberOfPoints = 0;    // output points
  const Id* Source = nullptr;      // output point -> finer-level point; null: the same id
  const Id* Map = nullptr;         // finer-level point -> row of the coarser arrays; null: same
  const double* Weights = nullptr; // per output point; null: `Weight` for every point
  double Weight = 0.0;
  ArrayPool* Pool = nullptr;       // where output arrays come from; null: new arrays
  // An array of the finer level that keeps its own values (as if the coarser level lacked it).
  vtkAbstractArray* Unblended = nullptr;

  double WeightOf(vtkIdType q) const { return this->Weights ? this->Weights[q] : this->Weight; }
};

/// (1 - w) a + w b for floating-point arrays, in a's type, computed in double (so w = 0 gives a
/// and w = 1 gives b exactly), one vtkSMPTools loop. With `renormalize`, 3-component tuples
/// are scaled back to unit length (normals).
VTKFILTERSMESHLOD_EXPORT vtkSmartPointer<vtkDataArray> BlendRealArray(
  vtkDataArray* a, vtkDataArray* b, const BlendPlan& plan, bool renormalize);

/// Arrays that are not interpolated (integers: ids, labels; strings): b's value where w >= 0.5,
/// a's value elsewhere (a's value everywhere when b is null).
VTKFILTERSMESHLOD_EXPORT vtkSmartPointer<vtkAbstractArray> SwitchArray(
  vtkAbstractArray* a, vtkAbstractArray* b, const BlendPlan& plan);

/// Every array of `fine` except the morph arrays, blended with the array of the same name and
/// number of components in `coarse` (floating-point arrays blended, the others switched; an
/// array `coarse` lacks keeps the finer level's values, and so does the GlobalIds attribute,
/// which must stay unique). Attributes are kept; Normals are renormalised. Arrays are shared,
/// not copied, wherever the output equals them.
VTKFILTERSMESHLOD_EXPORT void BlendPointData(
  vtkPointData* fine, vtkPointData* coarse, const BlendPlan& plan, vtkPointData* out);

/// For every array of `fine` (but the morph arrays) that has a counterpart in `coarse` (as
/// BlendPointData pairs them), that counterpart's rows map[q], q < numberOfPoints, gathered
/// into `out` under the same name: each point's values where it goes. Arrays without a
/// counterpart are left out. Normals are renormalised, like BlendPointData's at weight 1.
VTKFILTERSMESHLOD_EXPORT void GatherPointData(
  vtkPointData* fine, vtkPointData* coarse, const Id* map, vtkIdType numberOfPoints,
  vtkPointData* out);

/// Whether the array is one of the hierarchy's morph arrays (MorphTarget, MorphTargetId,
/// CollapseRank), which a geomorph's output does not carry.
VTKFILTERSMESHLOD_EXPORT bool IsMorphArray(const char* name);
} // namespace meshlod

#endif
