#include "MeshLODBlend.h"

#include "MeshLODHierarchy.h"
#include "MeshLODNewArray.h"

#include "vtkArrayDispatch.h"
#include "vtkDataArray.h"
#include "vtkDataArrayRange.h"
#include "vtkPointData.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace meshlod
{
namespace
{
bool IsReal(vtkAbstractArray* array)
{
  return vtkDataArray::SafeDownCast(array) &&
    (array->GetDataType() == VTK_FLOAT || array->GetDataType() == VTK_DOUBLE);
}


// Output rows: which finer-level row (A), coarser row (B) and weight output point q takes.
// Specialised on the plan's indirections, so the common cases have no branch per point.
template <bool HasSource, bool HasMap, bool HasWeights>
struct Rows
{
  const BlendPlan& Plan;
  vtkIdType A(vtkIdType q) const { return HasSource ? this->Plan.Source[q] : q; }
  vtkIdType B(vtkIdType a) const { return HasMap ? this->Plan.Map[a] : a; }
  double W(vtkIdType q) const { return HasWeights ? this->Plan.Weights[q] : this->Plan.Weight; }
};

// Scale the 3-component tuples [begin, end) back to unit length, in place. Branch-free, so that
// the compiler turns it into vector square roots and divisions (see the compile options of this
// file): one scalar square root and division per tuple cost more than the blend itself.
template <typename T, typename Iterator>
void Renormalize(Iterator v, vtkIdType begin, vtkIdType end)
{
  for (vtkIdType q = begin; q < end; ++q)
  {
    const T x = v[3 * q], y = v[3 * q + 1], z = v[3 * q + 2];
    const T length2 = x * x + y * y + z * z;
    // A zero vector stays zero: the floor only keeps the division finite.
    constexpr T floor = std::numeric_limits<T>::min();
    const T scale = T(1) / std::sqrt(length2 > floor ? length2 : floor);
    v[3 * q] = x * scale;
    v[3 * q + 1] = y * scale;
    v[3 * q + 2] = z * scale;
  }
}

// (1 - w) a + w b. With `Careful`, where that is NaN from infinite values (inf - inf, 0 * inf)
// rather than a NaN value, the nearer end's value. Only arrays holding an infinity are blended
// carefully: the test in every step kept the loops from being vectorised (a frame of 200,000
// points and normals took 1.6 times as long).
template <bool Careful>
inline double Mix(double a, double b, double w)
{
  const double mixed = (1.0 - w) * a + w * b;
  if (Careful && std::isnan(mixed) && !std::isnan(a) && !std::isnan(b))
  {
    return w < 0.5 ? a : b;
  }
  return mixed;
}

// Whether any value of `array` is infinite (its ranges are cached by the array until it
// changes, so a level's arrays are scanned once, not per frame).
bool HoldsInfinity(vtkDataArray* array)
{
  for (int c = 0; c < array->GetNumberOfComponents(); ++c)
  {
    double range[2];
    array->GetRange(range, c);
    if (std::isinf(range[0]) || std::isinf(range[1]))
    {
      return true;
    }
  }
  return false;
}

// Three components (points, normals, vectors). With `renormalize`, each block of blended tuples
// is renormalised while it is still in cache.
template <bool Careful, typename RowsT, typename ARange, typename BRange, typename OutRange>
void Blend3(const RowsT& rows, const ARange& a, const BRange& b, OutRange& out, vtkIdType count,
  bool renormalize)
{
  using OutT = typename OutRange::value_type;
  constexpr vtkIdType Block = 512;
  vtkSMPTools::For(0, count, [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType first = begin; first < end; first += Block)
    {
      const vtkIdType last = std::min(end, first + Block);
      for (vtkIdType q = first; q < last; ++q)
      {
        const vtkIdType ia = rows.A(q);
        const vtkIdType ib = rows.B(ia);
        const double w = rows.W(q);
        for (vtkIdType c = 0; c < 3; ++c)
        {
          out[3 * q + c] = static_cast<OutT>(Mix<Careful>(
            static_cast<double>(a[3 * ia + c]), static_cast<double>(b[3 * ib + c]), w));
        }
      }
      if (renormalize)
      {
        Renormalize<OutT>(out.begin(), first, last);
      }
    }
  });
}

// Any number of components.
template <bool Careful, typename RowsT, typename ARange, typename BRange, typename OutRange>
void BlendN(
  const RowsT& rows, const ARange& a, const BRange& b, OutRange& out, vtkIdType count, int nc)
{
  using OutT = typename OutRange::value_type;
  vtkSMPTools::For(0, count, [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType q = begin; q < end; ++q)
    {
      const vtkIdType ia = rows.A(q);
      const vtkIdType ib = rows.B(ia);
      const double w = rows.W(q);
      for (int c = 0; c < nc; ++c)
      {
        out[q * nc + c] = static_cast<OutT>(Mix<Careful>(
          static_cast<double>(a[ia * nc + c]), static_cast<double>(b[ib * nc + c]), w));
      }
    }
  });
}

template <bool Careful, bool HasSource, bool HasMap, bool HasWeights, typename ARange,
  typename BRange, typename OutRange>
void BlendRows(
  const BlendPlan& plan, const ARange& a, const BRange& b, OutRange& out, int nc, bool renormalize)
{
  const Rows<HasSource, HasMap, HasWeights> rows{ plan };
  if (nc == 3)
  {
    Blend3<Careful>(rows, a, b, out, plan.NumberOfPoints, renormalize);
  }
  else
  {
    BlendN<Careful>(rows, a, b, out, plan.NumberOfPoints, nc);
  }
}

struct BlendWorker
{
  const BlendPlan* Plan;
  vtkDataArray* Out;
  bool Renormalize;

  template <typename AArray, typename BArray>
  void operator()(AArray* a, BArray* b) const
  {
    if (HoldsInfinity(a) || HoldsInfinity(b))
    {
      this->Blend<true>(a, b);
    }
    else
    {
      this->Blend<false>(a, b);
    }
  }

  template <bool Careful, typename AArray, typename BArray>
  void Blend(AArray* a, BArray* b) const
  {
    const auto ar = vtk::DataArrayValueRange(a);
    const auto br = vtk::DataArrayValueRange(b);
    // Out is a->NewInstance(): the same concrete class as a.
    auto outr = vtk::DataArrayValueRange(static_cast<AArray*>(this->Out));
    const int nc = a->GetNumberOfComponents();
    const BlendPlan& p = *this->Plan;
    const bool renormalize = this->Renormalize;
    if (!p.Source && !p.Map && !p.Weights && !renormalize)
    {
      // Same ids, one weight: a flat loop over the values.
      using OutT = typename decltype(outr)::value_type;
      const double w = p.Weight;
      vtkSMPTools::For(0, p.NumberOfPoints * nc, [&](vtkIdType begin, vtkIdType end) {
        for (vtkIdType v = begin; v < end; ++v)
        {
          outr[v] =
            static_cast<OutT>(Mix<Careful>(static_cast<double>(ar[v]), static_cast<double>(br[v]), w));
        }
      });
      return;
    }
    switch ((p.Source ? 4 : 0) + (p.Map ? 2 : 0) + (p.Weights ? 1 : 0))
    {
      case 0:
        BlendRows<Careful, false, false, false>(p, ar, br, outr, nc, renormalize);
        break;
      case 1:
        BlendRows<Careful, false, false, true>(p, ar, br, outr, nc, renormalize);
        break;
      case 2:
        BlendRows<Careful, false, true, false>(p, ar, br, outr, nc, renormalize);
        break;
      case 3:
        BlendRows<Careful, false, true, true>(p, ar, br, outr, nc, renormalize);
        break;
      case 4:
        BlendRows<Careful, true, false, false>(p, ar, br, outr, nc, renormalize);
        break;
      case 5:
        BlendRows<Careful, true, false, true>(p, ar, br, outr, nc, renormalize);
        break;
      case 6:
        BlendRows<Careful, true, true, false>(p, ar, br, outr, nc, renormalize);
        break;
      default:
        BlendRows<Careful, true, true, true>(p, ar, br, outr, nc, renormalize);
        break;
    }
  }
};

// Row of the finer array (a) or of the coarser one (b) that output point q takes.
struct SwitchRows
{
  const BlendPlan& Plan;
  bool HasB;

  bool TakesB(vtkIdType q) const { return this->HasB && this->Plan.WeightOf(q) >= 0.5; }
  vtkIdType RowA(vtkIdType q) const { return this->Plan.Source ? this->Plan.Source[q] : q; }
  vtkIdType RowB(vtkIdType q) const
  {
    const vtkIdType ia = this->RowA(q);
    return this->Plan.Map ? this->Plan.Map[ia] : ia;
  }
};

struct SwitchWorker
{
  const SwitchRows* Rows;
  vtkDataArray* Out;

  template <typename AArray, typename BArray>
  void operator()(AArray* a, BArray* b) const
  {
    const auto at = vtk::DataArrayTupleRange(a);
    const auto bt = vtk::DataArrayTupleRange(b);
    auto outt = vtk::DataArrayTupleRange(static_cast<AArray*>(this->Out));
    const SwitchRows& rows = *this->Rows;
    vtkSMPTools::For(0, outt.size(), [&](vtkIdType begin, vtkIdType end) {
      for (vtkIdType q = begin; q < end; ++q)
      {
        if (rows.TakesB(q))
        {
          outt[q] = bt[rows.RowB(q)];
        }
        else
        {
          outt[q] = at[rows.RowA(q)];
        }
      }
    });
  }
};

// The array of `coarse` matching `a` (same name, components and kind), or null.
vtkAbstractArray* Counterpart(vtkPointData* coarse, vtkAbstractArray* a)
{
  if (!coarse || !a->GetName())
  {
    return nullptr;
  }
  vtkAbstractArray* b = coarse->GetAbstractArray(a->GetName());
  if (!b || b->GetNumberOfComponents() != a->GetNumberOfComponents() || IsReal(a) != IsReal(b) ||
    (vtkDataArray::SafeDownCast(a) == nullptr) != (vtkDataArray::SafeDownCast(b) == nullptr))
  {
    return nullptr;
  }
  return b;
}
} // namespace

//------------------------------------------------------------------------------
vtkSmartPointer<vtkAbstractArray> ArrayPool::Take(vtkAbstractArray* like, vtkIdType tuples)
{
  // Bounded: a few frames' worth of arrays; beyond that, arrays nobody holds are dropped first.
  constexpr std::size_t MaximumArrays = 32;
  for (const vtkSmartPointer<vtkAbstractArray>& array : this->Arrays)
  {
    if (array->GetReferenceCount() == 1 && array->GetDataType() == like->GetDataType() &&
      array->GetArrayType() == like->GetArrayType() && array->IsA(like->GetClassName()) &&
      array->GetNumberOfComponents() == like->GetNumberOfComponents() &&
      array->GetNumberOfTuples() == tuples && SameComponentNames(array, like))
    {
      // (Same component names: an array cannot lose those of an earlier use.)
      CopyArrayDescription(like, array);
      array->Modified();
      return array;
    }
  }
  vtkSmartPointer<vtkAbstractArray> array = NewArrayLike(like, tuples);
  if (this->Arrays.size() >= MaximumArrays)
  {
    const auto idle = std::find_if(this->Arrays.begin(), this->Arrays.end(),
      [](const vtkSmartPointer<vtkAbstractArray>& a) { return a->GetReferenceCount() == 1; });
    this->Arrays.erase(idle != this->Arrays.end() ? idle : this->Arrays.begin());
  }
  this->Arrays.push_back(array);
  return array;
}

namespace
{
// An output array shaped like `like`: from the plan's pool, or new.
vtkSmartPointer<vtkAbstractArray> OutputArray(vtkAbstractArray* like, const BlendPlan& plan)
{
  if (plan.Pool)
  {
    return plan.Pool->Take(like, plan.NumberOfPoints);
  }
  return NewArrayLike(like, plan.NumberOfPoints);
}
} // namespace

//------------------------------------------------------------------------------
vtkSmartPointer<vtkDataArray> BlendRealArray(
  vtkDataArray* a, vtkDataArray* b, const BlendPlan& plan, bool renormalize)
{
  vtkSmartPointer<vtkDataArray> out = vtkDataArray::SafeDownCast(OutputArray(a, plan));
  renormalize = renormalize && a->GetNumberOfComponents() == 3;
  BlendWorker worker{ &plan, out, renormalize };
  using Reals = vtkArrayDispatch::Reals;
  if (!vtkArrayDispatch::Dispatch2ByValueType<Reals, Reals>::Execute(a, b, worker))
  {
    worker(a, b); // any other array implementation, through the generic API
  }
  return out;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkAbstractArray> SwitchArray(
  vtkAbstractArray* a, vtkAbstractArray* b, const BlendPlan& plan)
{
  vtkSmartPointer<vtkAbstractArray> out = OutputArray(a, plan);
  const SwitchRows rows{ plan, b != nullptr };
  auto* da = vtkDataArray::SafeDownCast(a);
  auto* db = vtkDataArray::SafeDownCast(b);
  if (da && (db || !b))
  {
    SwitchWorker worker{ &rows, vtkDataArray::SafeDownCast(out) };
    if (!vtkArrayDispatch::Dispatch2SameValueType::Execute(da, db ? db : da, worker))
    {
      worker(da, db ? db : da);
    }
    return out;
  }
  // String and other non-numeric arrays: one tuple at a time.
  for (vtkIdType q = 0; q < plan.NumberOfPoints; ++q)
  {
    if (rows.TakesB(q))
    {
      out->SetTuple(q, rows.RowB(q), b);
    }
    else
    {
      out->SetTuple(q, rows.RowA(q), a);
    }
  }
  return out;
}

//------------------------------------------------------------------------------
void BlendPointData(
  vtkPointData* fine, vtkPointData* coarse, const BlendPlan& plan, vtkPointData* out)
{
  out->Initialize();
  const bool sameRows = plan.Source == nullptr && plan.Weights == nullptr;
  for (int i = 0; i < fine->GetNumberOfArrays(); ++i)
  {
    vtkAbstractArray* a = fine->GetAbstractArray(i);
    if (IsMorphArray(a->GetName()))
    {
      continue;
    }
    // Global ids keep the finer level's values: switched to the coarser level's, the points
    // that merge into one would share its id, and global ids must be unique.
    const bool own = a == plan.Unblended || a == fine->GetGlobalIds();
    vtkAbstractArray* b = own ? nullptr : Counterpart(coarse, a);
    vtkSmartPointer<vtkAbstractArray> result;
    if (sameRows && (plan.Weight == 0.0 || !b || (!IsReal(a) && plan.Weight < 0.5)))
    {
      result = a; // the output equals the finer level's array: share it
    }
    else if (IsReal(a) && b)
    {
      const bool normals = a == fine->GetNormals();
      result =
        BlendRealArray(vtkDataArray::SafeDownCast(a), vtkDataArray::SafeDownCast(b), plan, normals);
    }
    else
    {
      result = SwitchArray(a, b, plan);
    }
    const int attribute = fine->IsArrayAnAttribute(i);
    if (attribute >= 0)
    {
      out->SetAttribute(result, attribute);
    }
    else
    {
      out->AddArray(result);
    }
  }
}

//------------------------------------------------------------------------------
void GatherPointData(vtkPointData* fine, vtkPointData* coarse, const Id* map,
  vtkIdType numberOfPoints, vtkPointData* out)
{
  // A blend at weight 1 through the map is the gather: exactly the coarser values.
  BlendPlan gather;
  gather.NumberOfPoints = numberOfPoints;
  gather.Map = map;
  gather.Weight = 1.0;
  out->Initialize();
  for (int i = 0; i < fine->GetNumberOfArrays(); ++i)
  {
    vtkAbstractArray* a = fine->GetAbstractArray(i);
    vtkAbstractArray* b = IsMorphArray(a->GetName()) ? nullptr : Counterpart(coarse, a);
    if (!b)
    {
      continue;
    }
    if (IsReal(a))
    {
      out->AddArray(BlendRealArray(vtkDataArray::SafeDownCast(a), vtkDataArray::SafeDownCast(b),
        gather, a == fine->GetNormals()));
    }
    else
    {
      out->AddArray(SwitchArray(a, b, gather));
    }
  }
}

//------------------------------------------------------------------------------
bool IsMorphArray(const char* name)
{
  return name &&
    (!std::strcmp(name, names::MorphTarget) || !std::strcmp(name, names::MorphTargetId) ||
      !std::strcmp(name, names::CollapseRank));
}

} // namespace meshlod
