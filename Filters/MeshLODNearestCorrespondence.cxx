#include "MeshLODNearestCorrespondence.h"

#include "vtkIdList.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkStaticPointLocator.h"

#include <algorithm>
#include <limits>
#include <memory>

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

// The nearest fine point to x that `owner` leaves free (the lowest id among equally near ones),
// if it is among the ClosestAsked nearest fine points and no point beyond them could tie with it;
// else InvalidId.
constexpr int ClosestAsked = 16;
Id NearestFreeAmongClosest(
  const PointSearch& search, const double x[3], const std::vector<Id>& owner, vtkIdList* nearest)
{
  vtkPoints* points = search.Cloud->GetPoints();
  const vtkIdType n = points->GetNumberOfPoints();
  search.Locator->FindClosestNPoints(static_cast<int>(std::min<vtkIdType>(ClosestAsked, n)), x,
    nearest);
  Id best = InvalidId;
  double bestDistance2 = 0.0;
  for (vtkIdType i = 0; i < nearest->GetNumberOfIds(); ++i)
  {
    const vtkIdType f = nearest->GetId(i);
    double y[3];
    points->GetPoint(f, y);
    const double d2 = vtkMath::Distance2BetweenPoints(x, y);
    if (best != InvalidId && d2 > bestDistance2)
    {
      return best; // the points are in order of distance: nothing nearer follows
    }
    if (owner[f] == InvalidId && (best == InvalidId || f < best))
    {
      best = static_cast<Id>(f);
      bestDistance2 = d2;
    }
  }
  // The last point may tie with one not asked for (unless all were asked).
  return nearest->GetNumberOfIds() == n ? best : InvalidId;
}

// The points not taken yet, for "the nearest free point" queries that take what they find: a
// k-d tree whose nodes count their free points, so that the search skips the parts where all are
// taken. (Asking a locator for ever more nearest points until a free one turns up took time
// cubic in the point count when most of the near points were taken: levels that do not
// overlap, or a coarse level listed first.)
class FreePointTree
{
public:
  FreePointTree(vtkPoints* points, const std::vector<Id>& owner)
  {
    const Id n = static_cast<Id>(points->GetNumberOfPoints());
    this->Xyz.resize(3 * static_cast<size_t>(n));
    for (Id p = 0; p < n; ++p)
    {
      points->GetPoint(p, &this->Xyz[3 * static_cast<size_t>(p)]);
    }
    this->Taken.resize(n);
    this->Order.resize(n);
    this->LeafOf.resize(n);
    for (Id p = 0; p < n; ++p)
    {
      this->Taken[p] = owner[p] != InvalidId;
      this->Order[p] = p;
    }
    this->Nodes.resize(1);
    this->Build(0, 0, n, -1);
  }

  // The free point nearest to x (the lowest id among equally near ones), now taken; InvalidId
  // when none is free.
  Id TakeNearest(const double x[3])
  {
    double best = std::numeric_limits<double>::infinity();
    Id bestPoint = InvalidId;
    std::vector<Id>& stack = this->Stack;
    stack.assign(1, 0);
    while (!stack.empty())
    {
      const Node& node = this->Nodes[stack.back()];
      stack.pop_back();
      if (node.Free == 0 || (bestPoint != InvalidId && BoxDistance2(node, x) > best))
      {
        continue;
      }
      if (node.Left < 0)
      {
        for (Id i = node.Begin; i < node.End; ++i)
        {
          const Id p = this->Order[i];
          const double d = vtkMath::Distance2BetweenPoints(x, &this->Xyz[3 * size_t(p)]);
          // (The first free point is taken whatever its distance: squares of coordinates beyond
          // 1e154 overflow to infinity.)
          const bool nearer = bestPoint == InvalidId || d < best || (d == best && p < bestPoint);
          if (!this->Taken[p] && nearer)
          {
            best = d;
            bestPoint = p;
          }
        }
        continue;
      }
      // The nearer child is searched first (pushed last).
      const Id left = node.Left;
      const bool leftNearer = BoxDistance2(this->Nodes[left], x) <=
        BoxDistance2(this->Nodes[left + 1], x);
      stack.push_back(leftNearer ? left + 1 : left);
      stack.push_back(leftNearer ? left : left + 1);
    }
    if (bestPoint != InvalidId)
    {
      this->Taken[bestPoint] = true;
      for (Id node = this->LeafOf[bestPoint]; node >= 0; node = this->Nodes[node].Parent)
      {
        --this->Nodes[node].Free;
      }
    }
    return bestPoint;
  }

private:
  struct Node
  {
    double Low[3];
    double High[3];
    Id Begin, End; // the node's points: Order[Begin, End)
    Id Free;       // how many of them are not taken
    Id Parent;     // -1 at the root
    Id Left;       // the children are Left and Left + 1; -1 for a leaf
  };
  static constexpr Id LeafSize = 8;

  static double BoxDistance2(const Node& node, const double x[3])
  {
    double d = 0.0;
    for (int k = 0; k < 3; ++k)
    {
      const double gap = std::max({ node.Low[k] - x[k], 0.0, x[k] - node.High[k] });
      d += gap * gap;
    }
    return d;
  }

  // Nodes[index] (allocated already) over Order[begin, end), split at the median of its longest
  // side; its children go next to each other at the end of Nodes.
  void Build(Id index, Id begin, Id end, Id parent)
  {
    Node node{};
    node.Begin = begin;
    node.End = end;
    node.Parent = parent;
    node.Left = -1;
    for (int k = 0; k < 3; ++k)
    {
      node.Low[k] = std::numeric_limits<double>::infinity();
      node.High[k] = -std::numeric_limits<double>::infinity();
    }
    for (Id i = begin; i < end; ++i)
    {
      const double* x = &this->Xyz[3 * size_t(this->Order[i])];
      node.Free += this->Taken[this->Order[i]] ? 0 : 1;
      for (int k = 0; k < 3; ++k)
      {
        node.Low[k] = std::min(node.Low[k], x[k]);
        node.High[k] = std::max(node.High[k], x[k]);
      }
    }
    if (end - begin <= LeafSize)
    {
      for (Id i = begin; i < end; ++i)
      {
        this->LeafOf[this->Order[i]] = index;
      }
      this->Nodes[index] = node;
      return;
    }
    int axis = 0;
    for (int k = 1; k < 3; ++k)
    {
      axis = node.High[k] - node.Low[k] > node.High[axis] - node.Low[axis] ? k : axis;
    }
    const Id middle = begin + (end - begin) / 2;
    std::nth_element(this->Order.begin() + begin, this->Order.begin() + middle,
      this->Order.begin() + end, [&](Id a, Id b) {
        const double xa = this->Xyz[3 * size_t(a) + axis], xb = this->Xyz[3 * size_t(b) + axis];
        return xa < xb || (xa == xb && a < b);
      });
    node.Left = static_cast<Id>(this->Nodes.size());
    this->Nodes.resize(this->Nodes.size() + 2);
    this->Nodes[index] = node;
    this->Build(node.Left, begin, middle, index);
    this->Build(node.Left + 1, middle, end, index);
  }

  std::vector<double> Xyz;
  std::vector<bool> Taken;
  std::vector<Id> Order;
  std::vector<Id> LeafOf;
  std::vector<Node> Nodes;
  std::vector<Id> Stack;
};
} // namespace

//------------------------------------------------------------------------------
bool NearestVertexCorrespondence(vtkPoints* fine, vtkPoints* coarse, std::vector<Id>& partner,
  const std::function<bool()>& stop)
{
  const vtkIdType nf = fine->GetNumberOfPoints();
  const vtkIdType nc = coarse->GetNumberOfPoints();
  partner.assign(nf, InvalidId);
  if (nf == 0 || nc == 0)
  {
    return true;
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
    // The others take their nearest free fine point.
    // Most find one among their few nearest fine points, asked of the locator; the k-d tree of
    // the free points is built (once) for the first that does not, and answers the rest.
    std::sort(losers.begin(), losers.end());
    std::unique_ptr<FreePointTree> freePoints;
    vtkNew<vtkIdList> nearest;
    for (size_t i = 0; i < losers.size(); ++i)
    {
      if (stop && i % 1024 == 1023 && stop())
      {
        return false;
      }
      const Id c = losers[i];
      double x[3];
      coarse->GetPoint(c, x);
      Id f = freePoints ? InvalidId : NearestFreeAmongClosest(fineSearch, x, owner, nearest);
      if (f == InvalidId)
      {
        if (!freePoints)
        {
          freePoints.reset(new FreePointTree(fine, owner));
        }
        f = freePoints->TakeNearest(x);
      }
      if (f == InvalidId)
      {
        break; // every fine point is taken
      }
      owner[f] = c;
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
  return true;
}

} // namespace meshlod
