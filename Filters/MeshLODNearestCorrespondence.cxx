#include "MeshLODNearestCorrespondence.h"

#include "vtkIdList.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkStaticPointLocator.h"

#include <algorithm>

namespace meshlod
{
namespace
{
// A locator over the points alone (the locator wants a dataset).
struct PointSearch
{
  vtkNew<vtkPolyData> Cloud;
  vtkNew<vtkStaticPointLocator> Locator;

  explicit PointSearch(vtkPoints* points)
  {
    this->Cloud->SetPoints(points);
    this->Locator->SetDataSet(this->Cloud);
    this->Locator->BuildLocator(); // from this thread: the queries below are then thread safe
  }
};

double Distance2(vtkPoints* a, vtkIdType i, vtkPoints* b, vtkIdType j)
{
  double x[3], y[3];
  a->GetPoint(i, x);
  b->GetPoint(j, y);
  return vtkMath::Distance2BetweenPoints(x, y);
}
} // namespace

//------------------------------------------------------------------------------
void NearestVertexCorrespondence(vtkPoints* fine, vtkPoints* coarse, std::vector<Id>& partner)
{
  const vtkIdType nf = fine->GetNumberOfPoints();
  const vtkIdType nc = coarse->GetNumberOfPoints();
  partner.assign(nf, InvalidId);
  if (nf == 0 || nc == 0)
  {
    return;
  }

  // Step 1: every coarse point picks its nearest fine point.
  std::vector<Id> picked(nc);
  std::vector<double> pickedDistance2(nc);
  {
    PointSearch fineSearch(fine);
    vtkSMPTools::For(0, nc, [&](vtkIdType begin, vtkIdType end) {
      double x[3];
      for (vtkIdType c = begin; c < end; ++c)
      {
        coarse->GetPoint(c, x);
        const vtkIdType f = fineSearch.Locator->FindClosestPoint(x);
        picked[c] = static_cast<Id>(f);
        pickedDistance2[c] = Distance2(coarse, c, fine, f);
      }
    });
    // Conflicts: the nearest coarse point keeps the fine point (increasing c and a strict
    // comparison keep the lowest id on ties).
    std::vector<Id>& owner = partner;
    std::vector<Id> losers;
    for (vtkIdType c = 0; c < nc; ++c)
    {
      Id& current = owner[picked[c]];
      if (current == InvalidId || pickedDistance2[c] < pickedDistance2[current])
      {
        if (current != InvalidId)
        {
          losers.push_back(current);
        }
        current = static_cast<Id>(c);
      }
      else
      {
        losers.push_back(static_cast<Id>(c));
      }
    }
    // The others take their nearest free fine point, searching ever more neighbours.
    std::sort(losers.begin(), losers.end());
    vtkNew<vtkIdList> nearest;
    for (const Id c : losers)
    {
      double x[3];
      coarse->GetPoint(c, x);
      bool placed = false;
      for (vtkIdType n = 8; !placed; n *= 2)
      {
        const vtkIdType asked = std::min(n, nf);
        fineSearch.Locator->FindClosestNPoints(static_cast<int>(asked), x, nearest);
        for (vtkIdType i = 0; i < nearest->GetNumberOfIds() && !placed; ++i)
        {
          const vtkIdType f = nearest->GetId(i);
          if (owner[f] == InvalidId)
          {
            owner[f] = c;
            placed = true;
          }
        }
        if (asked == nf)
        {
          break; // every fine point is taken
        }
      }
    }
  }

  // Step 2: fine points without a partner take their nearest coarse point.
  PointSearch coarseSearch(coarse);
  vtkSMPTools::For(0, nf, [&](vtkIdType begin, vtkIdType end) {
    double x[3];
    for (vtkIdType f = begin; f < end; ++f)
    {
      if (partner[f] == InvalidId)
      {
        fine->GetPoint(f, x);
        partner[f] = static_cast<Id>(coarseSearch.Locator->FindClosestPoint(x));
      }
    }
  });
}

} // namespace meshlod
