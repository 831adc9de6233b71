#include "MeshLODBlend.h"

#include "MeshLODHierarchy.h"

#include "vtkArrayDispatch.h"
#include "vtkDataArray.h"
#include "vtkDataArrayRange.h"
#include "vtkPointData.h"
#include "vtkSMPTools.h"

#include <cmath>
#include <cstring>

namespace meshlod
{
namespace
{
bool IsReal(vtkAbstractArray* array)
{
  return vtkDataArray::SafeDownCast(array) &&
    (array->GetDataType() == VTK_FLOAT || array->GetDataType() == VTK_DOUBLE);
}

bool IsMorphArray(const char* name)
{
  return name &&
    (!std::strcmp(name, names::MorphTarget) || !std::strcmp(name, names::MorphTargetId) ||
      !std::strcmp(name, names::CollapseRank));
}

void Renormalize(double* v)
{
  const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (length > 0.0)
  {
    v[0] /= length;
    v[1] /= length;
    v[2] /= length;
  }
}

// The blend loop, specialised on which indirections the plan has so that the common case
// (same ids, one weight) is a plain loop over values.
template<bool HasSource, bool HasMap, bool HasWeights>
struct BlendKernel
{
  template<typename ARange, typename BRange, typename OutRange>
  static void Run(const ARange& a, const BRange& b, OutRange& out, const BlendPlan& plan, int nc,
    bool renormalize)
  {
    using OutT = typename OutRange::value_type;
    vtkSMPTools::For(0, plan.NumberOfPoints,
      [&](vtkIdType begin, vtkIdType end)
      {
        double tuple[16];
        for (vtkIdType q = begin; q < end; ++q)
        {
          const vtkIdType ia = HasSource ? plan.Source[q] : q;
          const vtkIdType ib = HasMap ? plan.Map[ia] : ia;
          const double w = HasWeights ? plan.Weights[q] : plan.Weight;
          for (int c = 0; c < nc; ++c)
          {
            const double x = (1.0 - w) * static_cast<double>(a[ia * nc + c]) +
              w * static_cast<double>(b[ib * nc + c]);
            if (renormalize)
            {
              tuple[c] = x;
            }
            else
            {
              out[q * nc + c] = static_cast<OutT>(x);
            }
          }
          if (renormalize)
          {
            Renormalize(tuple);
            for (int c = 0; c < nc; ++c)
            {
              out[q * nc + c] = static_cast<OutT>(tuple[c]);
            }
          }
        }
      });
  }
};

struct BlendWorker
{
  const BlendPlan* Plan;
  vtkDataArray* Out;
  bool Renormalize;

  template<typename AArray, typename BArray>
  void operator()(AArray* a, BArray* b) const
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
      vtkSMPTools::For(0, p.NumberOfPoints * nc,
        [&](vtkIdType begin, vtkIdType end)
        {
          for (vtkIdType v = begin; v < end; ++v)
          {
            outr[v] = static_cast<OutT>(
              (1.0 - w) * static_cast<double>(ar[v]) + w * static_cast<double>(br[v]));
          }
        });
      return;
    }
    const int variant = (p.Source ? 4 : 0) + (p.Map ? 2 : 0) + (p.Weights ? 1 : 0);
    switch (variant)
    {
      case 0:
        BlendKernel<false, false, false>::Run(ar, br, outr, p, nc, renormalize);
        break;
      case 1:
        BlendKernel<false, false, true>::Run(ar, br, outr, p, nc, renormalize);
        break;
      case 2:
        BlendKernel<false, true, false>::Run(ar, br, outr, p, nc, renormalize);
        break;
      case 3:
        BlendKernel<false, true, true>::Run(ar, br, outr, p, nc, renormalize);
        break;
      case 4:
        BlendKernel<true, false, false>::Run(ar, br, outr, p, nc, renormalize);
        break;
      case 5:
        BlendKernel<true, false, true>::Run(ar, br, outr, p, nc, renormalize);
        break;
      case 6:
        BlendKernel<true, true, false>::Run(ar, br, outr, p, nc, renormalize);
        break;
      default:
        BlendKernel<true, true, true>::Run(ar, br, outr, p, nc, renormalize);
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

  template<typename AArray, typename BArray>
  void operator()(AArray* a, BArray* b) const
  {
    const auto at = vtk::DataArrayTupleRange(a);
    const auto bt = vtk::DataArrayTupleRange(b);
    auto outt = vtk::DataArrayTupleRange(static_cast<AArray*>(this->Out));
    const SwitchRows& rows = *this->Rows;
    vtkSMPTools::For(0, outt.size(),
      [&](vtkIdType begin, vtkIdType end)
      {
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
vtkSmartPointer<vtkDataArray> BlendRealArray(
  vtkDataArray* a, vtkDataArray* b, const BlendPlan& plan, bool renormalize)
{
  auto out = vtk::TakeSmartPointer(a->NewInstance());
  out->SetName(a->GetName());
  out->SetNumberOfComponents(a->GetNumberOfComponents());
  out->SetNumberOfTuples(plan.NumberOfPoints);
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
  auto out = vtk::TakeSmartPointer(a->NewInstance());
  out->SetName(a->GetName());
  out->SetNumberOfComponents(a->GetNumberOfComponents());
  out->SetNumberOfTuples(plan.NumberOfPoints);
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
    vtkAbstractArray* b = Counterpart(coarse, a);
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

} // namespace meshlod
