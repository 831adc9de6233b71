// Octree clustering: cuts of the cluster tree and the epsilon search (see OctreeClusteringInternals.h).
#include "FreshMemory.h"
#include "OctreeClusteringInternals.h"

#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <limits>

namespace meshlod
{
using namespace octree;

namespace
{
// CollectCut walks the tree below this many nodes or more at once.
constexpr std::size_t FrontierNodes = 256;
}

//------------------------------------------------------------------------------
// Activation[i]: the smallest threshold on the path from node i to its root. A node is collapsed
// (it or an ancestor is a cluster) exactly when epsilon reaches it.
void OctreeClustering::Internals::ComputeActivation(bool guess)
{
  // To guess an epsilon (not to cut), unevaluated nodes count with e1 raised by the ratio the
  // evaluations showed so far (e2 typically adds some 10%).
  const float inflation = static_cast<float>(
    guess && this->RatioCount > 0 ? std::exp(this->LogRatioSum / this->RatioCount) : 1.0);
  const Id ni = this->Tree.NumberOfInternalNodes();
  ResizeFresh(this->Activation, ni);
  // Parents before children, i.e. downwards by id (a parent has a larger id): the top tier on
  // one thread, then the cells of the bottom tier at once (see ClusterTree::CellNodeOffsets).
  const auto activate = [&](Id i) {
    const Id parent = this->Tree.Nodes[i].Parent;
    const float own =
      this->State[i] == NodeState::NotEvaluated ? this->Thr[i] * inflation : this->Thr[i];
    this->Activation[i] =
      parent == InvalidId ? own : std::min(own, this->Activation[parent - this->NV]);
  };
  const std::vector<Id>& cells = this->Tree.CellNodeOffsets;
  const Id topTier = cells.empty() ? 0 : cells.back();
  for (Id i = ni - 1; i >= topTier; --i)
  {
    activate(i);
  }
  vtkSMPTools::For(0, static_cast<Id>(cells.empty() ? 0 : cells.size() - 1), [&](Id begin, Id end) {
    for (Id c = begin; c < end; ++c)
    {
      for (Id i = cells[c + 1] - 1; i >= cells[c]; --i)
      {
        activate(i);
      }
    }
  });
}

//------------------------------------------------------------------------------
// The clusters at `epsilon`: the topmost nodes whose threshold is at most epsilon (a vertex on
// its own always qualifies), in depth-first order: a walk down from the roots that stops at
// them, which visits the nodes above the cut and the cut only.
void OctreeClustering::Internals::CollectCut(double epsilon, std::vector<Id>& cut) const
{
  const ClusterTree& tree = this->Tree;
  // The walk in two parts: from the roots down to a frontier of some hundreds of nodes (each
  // that does not qualify replaced by its children, in order), then below the frontier nodes
  // with vtkSMPTools, the parts joined in frontier order: the depth-first order of one walk.
  std::vector<Id> frontier(tree.Roots), next;
  for (bool expanded = true; expanded && frontier.size() < FrontierNodes;)
  {
    expanded = false;
    next.clear();
    for (const Id node : frontier)
    {
      if (this->Qualifies(node, epsilon))
      {
        next.push_back(node);
      }
      else
      {
        next.insert(next.end(), tree.ChildrenBegin(node), tree.ChildrenEnd(node));
        expanded = true;
      }
    }
    frontier.swap(next);
  }
  // (In at most FrontierNodes parts of consecutive frontier nodes: a tree with very many roots,
  // such as one per isolated vertex, is not walked one vector per root.)
  const std::int64_t nodes = static_cast<std::int64_t>(frontier.size());
  const Id parts = static_cast<Id>(std::min<std::int64_t>(nodes, FrontierNodes));
  auto partBegin = [&](Id part) { return static_cast<Id>(nodes * part / std::max<Id>(parts, 1)); };
  std::vector<std::vector<Id>> below(static_cast<std::size_t>(parts));
  vtkSMPTools::For(0, parts, 1, [&](Id begin, Id end) {
    std::vector<Id> stack;
    for (Id part = begin; part < end; ++part)
    {
      stack.assign(std::make_reverse_iterator(frontier.begin() + partBegin(part + 1)),
        std::make_reverse_iterator(frontier.begin() + partBegin(part)));
      while (!stack.empty())
      {
        const Id node = stack.back();
        stack.pop_back();
        if (this->Qualifies(node, epsilon))
        {
          below[part].push_back(node);
        }
        else
        {
          stack.insert(stack.end(), std::make_reverse_iterator(tree.ChildrenEnd(node)),
            std::make_reverse_iterator(tree.ChildrenBegin(node)));
        }
      }
    }
  });
  cut.clear();
  for (const std::vector<Id>& part : below)
  {
    cut.insert(cut.end(), part.begin(), part.end());
  }
}

//------------------------------------------------------------------------------
// The cut at `epsilon` with every cluster evaluated in full. An evaluation can only raise a
// node's threshold: a cluster that fails is replaced by the topmost nodes below it that qualify,
// which are evaluated in turn. With `update`, `cut` is the cut at the same epsilon before some of
// its nodes were refused or marked inadmissible: only those are replaced, which gives the same
// cut as starting afresh (the nodes above a cut node do not qualify, marked or not) without a
// pass over the whole tree.
void OctreeClustering::Internals::CutAt(double epsilon, std::vector<Id>& cut, bool update)
{
  if (!update)
  {
    this->CollectCut(epsilon, cut);
  }
  vtkSMPThreadLocal<EvaluationScratch> scratch;
  std::vector<Id> pending, failed, kept, stack;
  std::vector<Id> candidates;
  candidates.swap(cut);
  for (;;)
  {
    pending.clear();
    failed.clear();
    this->TriageCandidates(candidates, epsilon, pending, kept, failed);
    if (pending.empty() && failed.empty())
    {
      break;
    }
    vtkSMPTools::For(0,
      static_cast<Id>(pending.size()),
      [&](Id begin, Id end)
      {
        EvaluationScratch& local = scratch.Local();
        for (Id j = begin; j < end; ++j)
        {
          this->Evaluate(pending[j] - this->NV, local);
        }
      });
    this->RecordEvaluations(pending);
    candidates.clear();
    for (const Id node : pending)
    {
      if (this->Thr[node - this->NV] <= epsilon)
      {
        kept.push_back(node);
      }
      else
      {
        this->DescendToQualifying(node, epsilon, stack, candidates);
      }
    }
    for (const Id node : failed)
    {
      this->DescendToQualifying(node, epsilon, stack, candidates);
    }
  }
  cut.swap(kept);
  vtkSMPTools::Sort(cut.begin(),
    cut.end(),
    [&](Id a, Id b) { return this->Tree.Position(a) < this->Tree.Position(b); });
}

//------------------------------------------------------------------------------
// CutAt's candidates sorted out: the nodes to evaluate (each given a slot, serially) into
// `pending`, those that qualify into `kept` and the others into `failed`.
void OctreeClustering::Internals::TriageCandidates(const std::vector<Id>& candidates,
  double epsilon,
  std::vector<Id>& pending,
  std::vector<Id>& kept,
  std::vector<Id>& failed)
{
  for (const Id node : candidates)
  {
    if (node >= this->NV && this->State[node - this->NV] == NodeState::NotEvaluated &&
      !this->Refused[node - this->NV])
    {
      const Id i = node - this->NV;
      pending.push_back(node);
      this->NewSlot(i);
    }
    else if (this->Qualifies(node, epsilon))
    {
      kept.push_back(node);
    }
    else
    {
      failed.push_back(node); // refused since its evaluation, or before it (update only)
    }
  }
}

//------------------------------------------------------------------------------
// After the nodes `evaluated` were: their count, and the logarithms of their errors over e1 by
// which ComputeActivation's guesses raise the e1 of the nodes not evaluated yet.
void OctreeClustering::Internals::RecordEvaluations(const std::vector<Id>& evaluated)
{
  this->Evaluated += static_cast<Id>(evaluated.size());
  for (const Id node : evaluated)
  {
    const Id i = node - this->NV;
    const float e1 = this->Tree.Nodes[i].E1;
    const double error = this->NodeError(node);
    if (this->State[i] == NodeState::Admissible && e1 > 0.0f && error > 0.0)
    {
      this->LogRatioSum += std::log(error / e1);
      ++this->RatioCount;
    }
  }
}

//------------------------------------------------------------------------------
// Replace a node that does not qualify by the topmost qualifying nodes below it, appended to
// `into` (`stack`: room for the walk, kept from one call to the next).
void OctreeClustering::Internals::DescendToQualifying(
  Id node, double epsilon, std::vector<Id>& stack, std::vector<Id>& into) const
{
  stack.assign(1, node);
  while (!stack.empty())
  {
    const Id parent = stack.back();
    stack.pop_back();
    for (const Id* c = this->Tree.ChildrenBegin(parent); c != this->Tree.ChildrenEnd(parent); ++c)
    {
      const Id child = *c;
      if (this->Qualifies(child, epsilon))
      {
        into.push_back(child);
      }
      else
      {
        stack.push_back(child);
      }
    }
  }
}

//------------------------------------------------------------------------------
// Positive floats order like their bit patterns: bin by the leading bits above `lo` (bin 0 holds
// `lo` and below), as many as keep the bins from `lo` to `hi` under Count.
struct OctreeClustering::Internals::ActivationBins
{
  static constexpr int Count = 4096;
  float Low;
  std::uint32_t Base;
  int Shift = 0;

  static std::uint32_t Bits(float a)
  {
    std::uint32_t u;
    std::memcpy(&u, &a, sizeof(u));
    return u;
  }
  ActivationBins(double lo, double hi)
    : Low(static_cast<float>(lo))
    , Base(Bits(static_cast<float>(lo)))
  {
    const std::uint32_t range = Bits(static_cast<float>(hi)) - this->Base;
    while ((range >> this->Shift) >= static_cast<std::uint32_t>(Count - 1))
    {
      ++this->Shift;
    }
  }
  int operator()(float a) const
  {
    return a <= this->Low ? 0 : 1 + static_cast<int>((Bits(a) - this->Base) >> this->Shift);
  }
};

//------------------------------------------------------------------------------
// The smallest epsilon whose cut keeps at most `target` input triangles by the estimate
// NT - (triangles that degenerate in collapsed nodes), from a histogram of the activation
// epsilons (no sort of all nodes). Needs ComputeActivation(). Returns infinity when even
// collapsing every mergeable node keeps more.
double OctreeClustering::Internals::EpsilonForCount(Id target) const
{
  const std::int64_t need = static_cast<std::int64_t>(this->NT) - target;
  if (need <= 0)
  {
    return 0.0;
  }
  // Three parallel passes over the nodes that can collapse (sums, minima and maxima: the same
  // for any thread count): ActivationSpan, ActivationHistogram and EpsilonInBin.
  double lo = 0.0, hi = 0.0;
  std::int64_t total = 0;
  this->ActivationSpan(lo, hi, total);
  if (total < need)
  {
    return std::numeric_limits<double>::infinity();
  }
  if (!(hi > 0.0))
  {
    return 0.0;
  }
  const ActivationBins bin(lo, hi);
  const std::vector<std::int64_t> histogram = this->ActivationHistogram(bin);
  std::int64_t before = 0;
  int b = 0;
  for (; b < ActivationBins::Count && before + histogram[b] < need; ++b)
  {
    before += histogram[b];
  }
  return this->EpsilonInBin(bin, b, before, need, hi);
}

//------------------------------------------------------------------------------
// Whether internal node i counts in EpsilonForCount: triangles degenerate in it, and it
// collapses at a finite epsilon.
bool OctreeClustering::Internals::CountsForEstimate(Id i) const
{
  return this->Tree.Nodes[i].Dies > 0 && this->Activation[i] < Infinite;
}

//------------------------------------------------------------------------------
// Over the nodes that count (CountsForEstimate): the triangles that degenerate in them in all
// (`total`), and the smallest and largest of their positive activations (`lo` is the largest
// double and `hi` 0 when none is positive).
void OctreeClustering::Internals::ActivationSpan(double& lo, double& hi, std::int64_t& total) const
{
  const Id ni = this->Tree.NumberOfInternalNodes();
  struct Span
  {
    double Low = std::numeric_limits<double>::max();
    double High = 0.0;
    std::int64_t Total = 0;
  };
  vtkSMPThreadLocal<Span> spans;
  vtkSMPTools::For(0, ni, [&](Id begin, Id end) {
    Span& span = spans.Local();
    for (Id i = begin; i < end; ++i)
    {
      const float a = this->Activation[i];
      if (this->CountsForEstimate(i))
      {
        span.Total += this->Tree.Nodes[i].Dies;
        if (a > 0.0f)
        {
          span.Low = std::min(span.Low, double(a));
          span.High = std::max(span.High, double(a));
        }
      }
    }
  });
  lo = std::numeric_limits<double>::max();
  hi = 0.0;
  total = 0;
  for (const Span& span : spans)
  {
    lo = std::min(lo, span.Low);
    hi = std::max(hi, span.High);
    total += span.Total;
  }
}

//------------------------------------------------------------------------------
// The triangles that degenerate in the nodes that count (CountsForEstimate), summed by the bin
// of their activation.
std::vector<std::int64_t> OctreeClustering::Internals::ActivationHistogram(
  const ActivationBins& bin) const
{
  const Id ni = this->Tree.NumberOfInternalNodes();
  vtkSMPThreadLocal<std::vector<std::int64_t>> histograms;
  vtkSMPTools::For(0, ni, [&](Id begin, Id end) {
    std::vector<std::int64_t>& local = histograms.Local();
    local.resize(ActivationBins::Count, 0);
    for (Id i = begin; i < end; ++i)
    {
      if (this->CountsForEstimate(i))
      {
        local[bin(this->Activation[i])] += this->Tree.Nodes[i].Dies;
      }
    }
  });
  std::vector<std::int64_t> histogram = FreshVector<std::int64_t>(ActivationBins::Count, 0);
  for (const std::vector<std::int64_t>& local : histograms)
  {
    for (std::size_t k = 0; k < local.size(); ++k)
    {
      histogram[k] += local[k];
    }
  }
  return histogram;
}

//------------------------------------------------------------------------------
// The activation at which the nodes of bin b, taken in order, bring the triangles that
// degenerate from `before` (those of the bins below b) to `need`; `hi` when they do not.
double OctreeClustering::Internals::EpsilonInBin(const ActivationBins& bin,
  int b,
  std::int64_t before,
  std::int64_t need,
  double hi) const
{
  const Id ni = this->Tree.NumberOfInternalNodes();
  // The nodes of that bin, sorted by (activation, triangles).
  const auto inThatBin = [&](Id i)
  { return this->CountsForEstimate(i) && bin(this->Activation[i]) == b; };
  const ParallelCompaction binNodes(ni, inThatBin);
  std::vector<std::pair<float, Id>> inBin(binNodes.Count());
  binNodes.Write(inThatBin,
    [&](Id i, Id slot) { inBin[slot] = { this->Activation[i], this->Tree.Nodes[i].Dies }; });
  std::sort(inBin.begin(), inBin.end());
  for (const auto& entry : inBin)
  {
    before += entry.second;
    if (before >= need)
    {
      return entry.first;
    }
  }
  return hi;
}

//------------------------------------------------------------------------------
// NT minus the triangles that degenerate at `epsilon`. Needs ComputeActivation().
std::int64_t OctreeClustering::Internals::EstimateAt(double epsilon) const
{
  vtkSMPThreadLocal<std::int64_t> vanishing(0);
  vtkSMPTools::For(0, this->Tree.NumberOfInternalNodes(), [&](Id begin, Id end) {
    std::int64_t& local = vanishing.Local();
    for (Id i = begin; i < end; ++i)
    {
      local += this->Activation[i] <= epsilon ? this->Tree.Nodes[i].Dies : 0;
    }
  });
  std::int64_t vanished = 0;
  for (const std::int64_t v : vanishing)
  {
    vanished += v;
  }
  return this->NT - vanished;
}

//------------------------------------------------------------------------------
// An epsilon (at least the current one) whose cut keeps about `target` triangles by the
// estimate. The estimate from e1 alone is a first guess (thresholds only rise when nodes are
// evaluated); then a bisection in log scale on the estimate with the cut evaluated.
double OctreeClustering::Internals::SearchEpsilon(Id target, Id tolerance)
{
  std::vector<Id> cut;
  auto estimate = [&](double epsilon)
  {
    this->CutAt(epsilon, cut);
    this->ComputeActivation();
    return this->EstimateAt(epsilon);
  };
  const double floor = this->CurrentEpsilon;
  double low = floor, high = 0.0;
  std::int64_t lowCount = this->NT, highCount = 0;
  for (int guess = 0; guess < 3; ++guess)
  {
    this->ComputeActivation(true);
    const double epsilon = std::max(floor, this->EpsilonForCount(target));
    if (!std::isfinite(epsilon))
    {
      return std::numeric_limits<float>::max(); // unreachable: collapse all that may collapse
    }
    const std::int64_t count = estimate(epsilon);
    if (std::abs(count - target) <= tolerance)
    {
      return epsilon;
    }
    if (count < target)
    {
      high = epsilon;
      highCount = count;
      break;
    }
    low = epsilon;
    lowCount = count;
  }
  if (!(high > 0.0))
  {
    // Grow until the estimate falls below the target.
    high = std::max(low, 1e-12 * this->Tree.Size);
    for (int it = 0; it < 60; ++it)
    {
      high *= 1.25;
      highCount = estimate(high);
      if (highCount <= target)
      {
        break;
      }
      low = high;
      lowCount = highCount;
    }
  }
  // The count falls about like a power of epsilon: interpolate in log-log (regula falsi), with a
  // bisection whenever the same end moved twice.
  int lastMoved = 0;
  for (int it = 0; it < 20 && high > low * (1.0 + 1e-7); ++it)
  {
    double next = low > 0.0 ? std::sqrt(low * high) : 0.5 * high;
    if (low > 0.0 && lastMoved != 2 && lastMoved != -2)
    {
      const double a = std::log(static_cast<double>(std::max<std::int64_t>(1, lowCount)));
      const double b = std::log(static_cast<double>(std::max<std::int64_t>(1, highCount)));
      const double t = a > b ? (a - std::log(static_cast<double>(target))) / (a - b) : 0.5;
      next = std::exp(
        std::log(low) + std::min(0.95, std::max(0.05, t)) * (std::log(high) - std::log(low)));
    }
    const std::int64_t count = estimate(next);
    if (std::abs(count - target) <= tolerance)
    {
      return next;
    }
    if (count > target)
    {
      low = next;
      lowCount = count;
      lastMoved = lastMoved < 0 ? lastMoved - 1 : -1;
    }
    else
    {
      high = next;
      highCount = count;
      lastMoved = lastMoved > 0 ? lastMoved + 1 : 1;
    }
    if (lastMoved == 3 || lastMoved == -3)
    {
      lastMoved = 0;
    }
  }
  return high;
}

} // namespace meshlod
