#include "MeshLODSurfaceDistance.h"
#include "MeshLODTriangleTree.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkMath.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkStaticCellLocator.h"
#include "vtkVersionMacros.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace meshlod
{
namespace
{
// Counter-based random numbers: sample i always gets the same values whatever thread draws it.
std::uint64_t SplitMix64(std::uint64_t x)
{
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

double Uniform(std::uint64_t seed, std::uint64_t counter)
{
  return (SplitMix64(seed ^ SplitMix64(counter)) >> 11) * (1.0 / 9007199254740992.0);
}

// The triangles of a polydata's polys as flat point-id triples (larger polygons fanned).
std::vector<vtkIdType> Triangles(vtkPolyData* mesh)
{
  std::vector<vtkIdType> tris;
  tris.reserve(3 * static_cast<size_t>(mesh->GetNumberOfPolys()));
  auto it = vtk::TakeSmartPointer(mesh->GetPolys()->NewIterator());
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
  {
    vtkIdType n;
    const vtkIdType* ids;
    it->GetCurrentCell(n, ids);
    for (vtkIdType k = 1; k + 1 < n; ++k)
    {
      tris.insert(tris.end(), { ids[0], ids[k], ids[k + 1] });
    }
  }
  return tris;
}

// Sample positions on `mesh`: area-uniform samples first, then (strided) vertices; the triangle
// of each area sample.
struct SampleSet
{
  std::vector<double> Positions;
  std::vector<vtkIdType> Triangles;
  std::int64_t AreaSamples = 0;
  std::uint64_t Seed = 0;
};

// The barycentric weights of area sample i on its triangle (uniform over the triangle).
void SampleWeights(std::uint64_t seed, std::int64_t i, double w[3])
{
  const double r1 = std::sqrt(Uniform(seed, 3 * i + 1));
  const double r2 = Uniform(seed, 3 * i + 2);
  w[0] = 1.0 - r1;
  w[1] = r1 * (1.0 - r2);
  w[2] = r1 * r2;
}

SampleSet Sample(vtkPolyData* mesh, const std::vector<vtkIdType>& tris,
  const SurfaceDistanceOptions& options, std::uint64_t seed)
{
  SampleSet samples;
  const vtkIdType nt = static_cast<vtkIdType>(tris.size() / 3);
  vtkPoints* points = mesh->GetPoints();
  std::vector<double> cumulative(nt + 1, 0.0);
  for (vtkIdType t = 0; t < nt; ++t)
  {
    double p[3][3];
    for (int k = 0; k < 3; ++k)
    {
      points->GetPoint(tris[3 * t + k], p[k]);
    }
    double e1[3], e2[3], n[3];
    vtkMath::Subtract(p[1], p[0], e1);
    vtkMath::Subtract(p[2], p[0], e2);
    vtkMath::Cross(e1, e2, n);
    cumulative[t + 1] = cumulative[t] + 0.5 * vtkMath::Norm(n);
  }
  const double totalArea = cumulative[nt];
  samples.AreaSamples = totalArea > 0.0 ? options.SamplesPerSurface : 0;
  samples.Seed = seed;

  const vtkIdType nv = points->GetNumberOfPoints();
  const vtkIdType stride = options.MaximumVertexSamples > 0
    ? std::max<vtkIdType>(1, (nv + options.MaximumVertexSamples - 1) / options.MaximumVertexSamples)
    : nv + 1;
  const vtkIdType vertexSamples = options.MaximumVertexSamples > 0 ? (nv + stride - 1) / stride : 0;

  samples.Positions.resize(3 * static_cast<size_t>(samples.AreaSamples + vertexSamples));
  samples.Triangles.resize(static_cast<size_t>(samples.AreaSamples));
  vtkSMPTools::For(0, samples.AreaSamples, [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType i = begin; i < end; ++i)
    {
      const double pick = Uniform(seed, 3 * i) * totalArea;
      vtkIdType t = std::upper_bound(cumulative.begin() + 1, cumulative.end(), pick) -
        (cumulative.begin() + 1);
      t = std::min(t, nt - 1);
      samples.Triangles[i] = t;
      double w[3];
      SampleWeights(seed, i, w);
      double* out = samples.Positions.data() + 3 * i;
      out[0] = out[1] = out[2] = 0.0;
      for (int k = 0; k < 3; ++k)
      {
        double p[3];
        points->GetPoint(tris[3 * t + k], p);
        for (int c = 0; c < 3; ++c)
        {
          out[c] += w[k] * p[c];
        }
      }
    }
  });
  for (vtkIdType j = 0; j < vertexSamples; ++j)
  {
    points->GetPoint(j * stride, samples.Positions.data() + 3 * (samples.AreaSamples + j));
  }
  return samples;
}

// The distance from p to a surface (exact to rounding whatever the triangle's shape, on one of
// zero area too: ClosestPointOnTriangle measures such a triangle by its edges).
double DistanceTo(const SurfaceTriangles& surface, const double p[3])
{
  double closest[3], dist2;
  surface.Tree.FindClosest(p, closest, dist2);
  return std::sqrt(dist2);
}

// The search of RefinedMaximum: from barycentric weights w on triangle `corner` (where the
// distance to `surface` is `start`), moves of `step` along the three edge directions (either
// way) to a farther point, the step halving when none is farther, from a quarter of the
// triangle down to 1/512 of it; at most MovesPerStep moves per step size, so at most
// 8 x (MovesPerStep + 1) x 6 = 3,120 distance queries (about 50 on the benchmark's levels; a
// ridge rising slowly along a triangle can take a few hundred).
constexpr int MovesPerStep = 64;

double ClimbOnTriangle(const SurfaceTriangles& surface, const double* corner[3], double w[3],
  double start)
{
  auto distanceAt = [&](const double at[3]) {
    double p[3];
    for (int c = 0; c < 3; ++c)
    {
      p[c] = at[0] * corner[0][c] + at[1] * corner[1][c] + at[2] * corner[2][c];
    }
    return DistanceTo(surface, p);
  };
  static const int moves[6][3] = { { 1, -1, 0 }, { -1, 1, 0 }, { 1, 0, -1 }, { -1, 0, 1 },
    { 0, 1, -1 }, { 0, -1, 1 } };
  double best = start;
  for (double step = 0.25; step >= 1.0 / 512.0; step *= 0.5)
  {
    for (int moved = 0; moved < MovesPerStep; ++moved)
    {
      bool farther = false;
      for (const auto& m : moves)
      {
        const double t[3] = { w[0] + m[0] * step, w[1] + m[1] * step, w[2] + m[2] * step };
        if (t[0] < 0.0 || t[1] < 0.0 || t[2] < 0.0)
        {
          continue;
        }
        const double d = distanceAt(t);
        if (d > best)
        {
          best = d;
          std::copy_n(t, 3, w);
          farther = true;
        }
      }
      if (!farther)
      {
        break;
      }
    }
  }
  return best;
}

// The area samples farthest from the other surface, refined: from the farthest sample of each
// of the RefinedSamples triangles whose farthest samples are farthest (ties by sample number,
// so that any thread count picks the same; a sample whose distance is not a number is left
// out), a search over its triangle climbs to the farthest point near it (ClimbOnTriangle). A
// far spot is often narrow (a fold of the other surface under a large triangle), and random
// samples land near it, not on it. Returns the largest distance found.
double RefinedMaximum(const SurfaceTriangles& surface, const SurfaceTriangles& sampled,
  const SampleSet& samples, const std::vector<double>& distance,
  const SurfaceDistanceOptions& options)
{
  if (options.RefinedSamples <= 0 || samples.AreaSamples <= 0)
  {
    return 0.0;
  }
  auto farther = [&](vtkIdType a, vtkIdType b)
  { return distance[a] != distance[b] ? distance[a] > distance[b] : a < b; };
  std::vector<vtkIdType> farthestOf(sampled.Triangles.size() / 3, -1);
  for (vtkIdType i = 0; i < samples.AreaSamples; ++i)
  {
    vtkIdType& slot = farthestOf[samples.Triangles[i]];
    if (distance[i] >= 0.0 && (slot < 0 || farther(i, slot)))
    {
      slot = i;
    }
  }
  std::vector<vtkIdType> starts;
  for (const vtkIdType i : farthestOf)
  {
    if (i >= 0)
    {
      starts.push_back(i);
    }
  }
  if (static_cast<std::int64_t>(starts.size()) > options.RefinedSamples)
  {
    std::nth_element(starts.begin(), starts.begin() + options.RefinedSamples, starts.end(), farther);
    starts.resize(static_cast<size_t>(options.RefinedSamples));
  }
  std::vector<double> found(starts.size(), 0.0);
  vtkSMPTools::For(0, static_cast<vtkIdType>(starts.size()), [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType k = begin; k < end; ++k)
    {
      const vtkIdType i = starts[k];
      const vtkIdType* ids = sampled.Triangles.data() + 3 * samples.Triangles[i];
      const double* corner[3] = { sampled.Points.data() + 3 * ids[0],
        sampled.Points.data() + 3 * ids[1], sampled.Points.data() + 3 * ids[2] };
      double w[3];
      SampleWeights(samples.Seed, i, w);
      found[k] = ClimbOnTriangle(surface, corner, w, distance[i]);
    }
  });
  return found.empty() ? 0.0 : *std::max_element(found.begin(), found.end());
}

// The maximum over all samples' distances (raised by RefinedMaximum) and the sum of squares
// over the area samples (over all samples for a surface of zero area, which has vertex samples
// only). Per-sample distances are stored first so the reduction order (and so the result) does
// not depend on the thread count.
void DistancesTo(const SurfaceTriangles& surface, const SurfaceTriangles& sampled,
  const SampleSet& samples, const SurfaceDistanceOptions& options, double& maximum,
  double& sumOfSquares)
{
  const vtkIdType count = static_cast<vtkIdType>(samples.Positions.size() / 3);
  std::vector<double> distance(count, 0.0);
  vtkSMPTools::For(0, count, [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType i = begin; i < end; ++i)
    {
      distance[i] = DistanceTo(surface, samples.Positions.data() + 3 * i);
    }
  });
  maximum = count > 0 ? *std::max_element(distance.begin(), distance.end()) : 0.0;
  maximum = std::max(maximum, RefinedMaximum(surface, sampled, samples, distance, options));
  const vtkIdType squared = samples.AreaSamples > 0 ? samples.AreaSamples : count;
  double sum = 0.0;
  for (vtkIdType i = 0; i < squared; ++i)
  {
    sum += distance[i] * distance[i];
  }
  sumOfSquares = sum;
}

// The number of samples RMS averages over (see DistancesTo).
double SquaredSampleCount(const SampleSet& samples)
{
  const std::int64_t count = samples.AreaSamples > 0
    ? samples.AreaSamples
    : static_cast<std::int64_t>(samples.Positions.size() / 3);
  return static_cast<double>(std::max<std::int64_t>(1, count));
}
} // namespace

//------------------------------------------------------------------------------
vtkSmartPointer<vtkStaticCellLocator> BuildCellLocator(vtkDataSet* cells)
{
  auto locator = vtkSmartPointer<vtkStaticCellLocator>::New();
  locator->SetDataSet(cells);
#if VTK_VERSION_NUMBER < VTK_VERSION_CHECK(9, 2, 0)
  // From VTK 9.2 the binning ignores the tolerance (and this setting is deprecated).
  locator->SetTolerance(0.001);
  locator->UseDiagonalLengthToleranceOn(); // the padding: that fraction of the diagonal
#endif
  locator->BuildLocator();
  return locator;
}

//------------------------------------------------------------------------------
struct SurfaceDistanceMeter::Internals
{
  SurfaceDistanceOptions Options;
  vtkSmartPointer<vtkPolyData> Reference;
  double Diagonal = 0.0;
  bool Empty = true;
  SampleSet Samples;
  SurfaceTriangles Surface;
};

SurfaceDistanceMeter::SurfaceDistanceMeter(
  vtkPolyData* reference, const SurfaceDistanceOptions& options)
  : Impl(new Internals)
{
  this->Impl->Options = options;
  this->Impl->Reference = reference;
  if (reference == nullptr)
  {
    return;
  }
  this->Impl->Diagonal = reference->GetNumberOfPoints() > 0 ? reference->GetLength() : 0.0;
  std::vector<vtkIdType> triangles = Triangles(reference);
  this->Impl->Empty = triangles.empty();
  if (!this->Impl->Empty)
  {
    this->Impl->Samples = Sample(reference, triangles, options, options.Seed);
    this->Impl->Surface.Build(reference->GetPoints(), std::move(triangles));
  }
}

SurfaceDistanceMeter::~SurfaceDistanceMeter() = default;

SurfaceDistance SurfaceDistanceMeter::Measure(vtkPolyData* other) const
{
  SurfaceDistance result;
  result.Diagonal = this->Impl->Diagonal;
  if (other == nullptr || this->Impl->Empty)
  {
    return result;
  }
  std::vector<vtkIdType> triangles = Triangles(other);
  if (triangles.empty())
  {
    return result;
  }
  const SurfaceDistanceOptions& options = this->Impl->Options;
  const SampleSet& samplesA = this->Impl->Samples;
  const SampleSet samplesB = Sample(other, triangles, options, SplitMix64(options.Seed));
  double sumAB = 0.0, sumBA = 0.0;
  SurfaceTriangles surface;
  surface.Build(other->GetPoints(), std::move(triangles));
  DistancesTo(surface, this->Impl->Surface, samplesA, options, result.MaxAB, sumAB);
  DistancesTo(this->Impl->Surface, surface, samplesB, options, result.MaxBA, sumBA);

  const double nA = SquaredSampleCount(samplesA);
  const double nB = SquaredSampleCount(samplesB);
  result.RmsAB = std::sqrt(sumAB / nA);
  result.RmsBA = std::sqrt(sumBA / nB);
  result.Hausdorff = std::max(result.MaxAB, result.MaxBA);
  result.Rms = std::sqrt((sumAB + sumBA) / (nA + nB));
  return result;
}

//------------------------------------------------------------------------------
SurfaceDistance MeasureSurfaceDistance(
  vtkPolyData* a, vtkPolyData* b, const SurfaceDistanceOptions& options)
{
  return SurfaceDistanceMeter(a, options).Measure(b);
}

} // namespace meshlod
