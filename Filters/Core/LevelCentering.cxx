#include "LevelCentering.h"

#include "FreshMemory.h"
#include "GroupByKey.h"
#include "Vector3.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace meshlod
{
namespace
{
// A sample projects into a triangle when no barycentric coordinate is below this.
constexpr double InsideTolerance = 1e-6;
// A shift is at most this fraction of the point's shortest edge.
constexpr double LargestShift = 0.25;
// A sample closer to a triangle than this fraction of the triangle's size lies on it (an input in
// single precision rounds at about 1e-7 of its coordinates); a shift below this fraction of the
// point's shortest edge is not made.
constexpr double OnSurface = 1e-5;
// A triangle turned by more than 60 degrees by the shifts undoes them.
constexpr double SmallestCosine = 0.5;
// A point with a triangle whose normal is farther than this from the point's normal (cosine of
// 35 degrees) sits on a crease or a corner, which its normal does not describe: not moved.
constexpr double SmoothCosine = 0.82;
// A projection counts as near a corner from this barycentric weight up: the surface there moves
// with the corner's shift.
constexpr double NearWeight = 1.0 / 3.0;
// Every second input triangle at most: its neighbours' centroids tell about as much.
constexpr Id MinimumStride = 2;
// Samples projected in one go (bounds the memory of the projections).
constexpr Id BlockSamples = 8192;

// Whether the triangles around a point close into one disc: each point of its link starts one
// link edge and ends one (so a boundary or non-manifold edge, or two fans, fail).
bool IsClosedDisc(const TriangleMesh& mesh, const VertexTriangleAdjacency& around, Id p)
{
  const Id count = around.Count(p);
  if (count < 3 || count > LevelCentering::MaximumValence)
  {
    return false;
  }
  Id starts[LevelCentering::MaximumValence], ends[LevelCentering::MaximumValence];
  const Id* fan = around.Of(p);
  for (Id i = 0; i < count; ++i)
  {
    const Id* tri = mesh.Triangle(fan[i]);
    const int k = tri[0] == p ? 0 : (tri[1] == p ? 1 : 2);
    starts[i] = tri[(k + 1) % 3];
    ends[i] = tri[(k + 2) % 3];
  }
  std::sort(starts, starts + count);
  std::sort(ends, ends + count);
  return std::equal(starts, starts + count, ends) &&
    std::adjacent_find(starts, starts + count) == starts + count;
}

// Points that did not change (their own single parent with weight 1) keep their shift of the
// previous level, added in the same rounding as there (so they land exactly where the previous
// level has them); the others start from none and are marked in `changed`.
void KeepUnchangedShifts(TriangleMesh& level, const std::vector<Id>& sourceOffsets,
  const std::vector<Id>& sourceParents, const std::vector<float>& sourceWeights,
  const std::vector<float>& previousShifts, std::vector<float>& shifts,
  std::vector<unsigned char>& changed)
{
  const Id points = level.GetNumberOfPoints();
  shifts = FreshVector<float>(3 * static_cast<size_t>(points), 0.0f);
  changed = FreshVector<unsigned char>(points, 1);
  vtkSMPTools::For(0, points, [&](Id begin, Id end) {
    for (Id p = begin; p < end; ++p)
    {
      const Id first = sourceOffsets[p];
      if (sourceOffsets[p + 1] != first + 1 || sourceWeights[first] != 1.0f)
      {
        continue;
      }
      changed[p] = 0;
      if (!previousShifts.empty())
      {
        for (int c = 0; c < 3; ++c)
        {
          shifts[3 * p + c] = previousShifts[3 * static_cast<size_t>(sourceParents[first]) + c];
          level.Points[3 * p + c] += static_cast<double>(shifts[3 * p + c]);
        }
      }
    }
  });
}

// Undo the shifts `own` (x, y, z per point) around triangles they would turn by more than 60
// degrees, until none does.
void UndoTurningShifts(const TriangleMesh& level, std::vector<float>& own)
{
  const Id triangles = level.GetNumberOfTriangles();
  std::vector<unsigned char> turned = FreshVector<unsigned char>(triangles, 0);
  for (bool again = true; again;)
  {
    vtkSMPTools::For(0, triangles, [&](Id begin, Id end) {
      for (Id t = begin; t < end; ++t)
      {
        const Id* tri = level.Triangle(t);
        double after[3][3];
        bool any = false;
        for (int c = 0; c < 3; ++c)
        {
          for (int k = 0; k < 3; ++k)
          {
            const float s = own[3 * tri[c] + k];
            any = any || s != 0.0f;
            after[c][k] = level.Point(tri[c])[k] + static_cast<double>(s);
          }
        }
        double before[3], now[3];
        level.AreaVector(t, before);
        Normal(after[0], after[1], after[2], now);
        turned[t] = any &&
          !(Dot(before, now) > SmallestCosine * std::sqrt(Dot(before, before) * Dot(now, now)));
      }
    });
    again = false;
    for (Id t = 0; t < triangles; ++t)
    {
      if (turned[t])
      {
        for (int c = 0; c < 3; ++c)
        {
          std::fill_n(own.data() + 3 * static_cast<size_t>(level.Triangle(t)[c]), 3, 0.0f);
        }
        again = true;
      }
    }
  }
}
} // namespace

// Per point: sums over the projections with a weight on it (weight = area times its
// barycentric weight) of weight times distance, of weight, of weight where the distance is 0,
// and of the barycentric weights alone (a count of samples); and the lowest and highest
// distance of the projections nearest to it (barycentric weight at least NearWeight).
struct LevelCentering::PointSums
{
  double Weighted, Weight;
  float OnSurface, Samples, Lowest, Highest;
};

// A triangle set up for projections: for w = x - Corner, the barycentric weights of corners 1
// and 2 of x's projection are w . B and w . C, and its signed distance is w . Unit.
struct LevelCentering::ProjectionFrame
{
  double Corner[3], B[3], C[3], Unit[3];
  double Size; // sqrt of twice the area
  bool Valid;

  void Set(const double* a, const double* b, const double* c)
  {
    double e1[3], e2[3], n[3];
    Subtract(b, a, e1);
    Subtract(c, a, e2);
    Cross(e1, e2, n);
    const double nn = Dot(n, n);
    this->Valid = nn > 0.0;
    if (!this->Valid)
    {
      return;
    }
    std::copy_n(a, 3, this->Corner);
    Cross(e2, n, this->B);
    Cross(n, e1, this->C);
    const double length = std::sqrt(nn);
    for (int k = 0; k < 3; ++k)
    {
      this->B[k] /= nn;
      this->C[k] /= nn;
      this->Unit[k] = n[k] / length;
    }
    this->Size = std::sqrt(length);
  }
};

// One sample's projection: the triangle it projects into, its signed distance (0 on the
// triangle) and the barycentric weights of the triangle's corners 1 and 2.
struct LevelCentering::Projection
{
  Id Triangle;
  float Area, Distance, B, C;
};

//------------------------------------------------------------------------------
// The samples are the input triangles' centroids, weighted by area: the mean of a linear
// function over a triangle is its value there. (The input's vertices, where the input surface
// passes through, stand for the surface around them only where it is flat: on a curved input the
// triangles between them lie below them by the input's own chordal error, and levels nearly as
// fine as the input were pushed out by it, 20% further from the input than uncentred at half
// the input's triangles.)
void LevelCentering::SetLevelZero(const LevelZeroCorrespondence& levelZero)
{
  this->LevelZero = &levelZero;
  this->Shifts.clear();
}

//------------------------------------------------------------------------------
void LevelCentering::Apply(TriangleMesh& level,
  const std::vector<Id>& sourceOffsets,
  const std::vector<Id>& sourceParents,
  const std::vector<float>& sourceWeights)
{
  const Id points = level.GetNumberOfPoints();

  // Levels with more than LargestFraction of the input's triangles stay as they are.
  if (level.GetNumberOfTriangles() > LargestFraction * this->LevelZero->Input.Triangles)
  {
    this->Shifts.clear();
    return;
  }

  const std::vector<float> previousShifts = std::move(this->Shifts);
  std::vector<float> shifts;
  std::vector<unsigned char> changed;
  KeepUnchangedShifts(
    level, sourceOffsets, sourceParents, sourceWeights, previousShifts, shifts, changed);
  VertexTriangleAdjacency around;
  around.Build(level);

  std::vector<PointSums> sums;
  // Each point's own distance to the input (in the samples' convention: positive when the input
  // lies beyond the point along its normal).
  std::vector<float> pointDistance;
  this->SumProjections(level, around, sums, pointDistance);

  // Each changed interior point's shift: along its normal by its weighted mean distance, at
  // most LargestShift of its shortest edge.
  std::vector<float> own = FreshVector<float>(3 * static_cast<size_t>(points), 0.0f);
  vtkSMPTools::For(0, points, [&](Id begin, Id end) {
    for (Id p = begin; p < end; ++p)
    {
      const PointSums& sum = sums[p];
      // Mostly on the triangles already (a planar facet): a few samples that project from
      // beyond the point's triangles onto a neighbouring facet must not move it.
      if (!changed[p] || sum.Samples < MinimumSamples || !(sum.Weight > 0.0) ||
        sum.OnSurface >= 0.5 * sum.Weight || !IsClosedDisc(level, around, p))
      {
        continue;
      }
      PointShift(level, around, p, sum, pointDistance[p], own.data() + 3 * p);
    }
  });
  Release(sums);
  Release(pointDistance);
  UndoTurningShifts(level, own);

  // The changed points' shifts, kept in single precision and added in one rounding, as the
  // points that keep them will be at the next level.
  for (Id p = 0; p < points; ++p)
  {
    if (own[3 * p] != 0.0f || own[3 * p + 1] != 0.0f || own[3 * p + 2] != 0.0f)
    {
      for (int c = 0; c < 3; ++c)
      {
        shifts[3 * p + c] = own[3 * p + c];
        level.Points[3 * p + c] += static_cast<double>(shifts[3 * p + c]);
      }
    }
  }
  this->Shifts = std::move(shifts);
}

//------------------------------------------------------------------------------
// The samples of each point (every stride-th input triangle, grouped by the point its first
// corner became, in input order), each projected into a triangle around its point (the nearest
// such; on a smooth fan projections fall into one triangle, or two that share the edge they lie
// on), its distance spread over that triangle's corners with the barycentric weights. Blocks of
// points in parallel, the sums in a fixed order.
void LevelCentering::SumProjections(const TriangleMesh& level,
  const VertexTriangleAdjacency& around, std::vector<PointSums>& sums,
  std::vector<float>& pointDistance) const
{
  const Id points = level.GetNumberOfPoints();
  const Id samplePoints = this->LevelZero->Input.Triangles;
  const Id stride =
    std::max<Id>(MinimumStride, samplePoints / std::max<Id>(1, SamplesPerPoint * points));
  std::vector<Id> sampleOffsets, samples;
  GroupByKey(
    static_cast<size_t>(points),
    [&](auto&& emit) {
      for (Id i = 0; i < samplePoints; i += stride)
      {
        emit(this->SamplePoint(i), i);
      }
    },
    sampleOffsets, samples);

  // Sample areas are kept in single precision in units of the diagonal squared: in world units
  // the centred levels strayed from the input for a mesh 1e21 across or 1e-21 across.
  const double areaUnit = SquaredLengthUnit(level.BoundingDiagonal());
  sums = FreshVector<PointSums>(points, PointSums{ 0.0, 0.0, 0.0f, 0.0f, 0.0f, 0.0f });
  pointDistance = FreshVector<float>(points, 0.0f);
  std::vector<Projection> projections; // grown as needed, each block writes all it reads
  for (Id first = 0, last = 0; first < points; first = last)
  {
    // The points whose samples fit in a block (at least one point).
    const Id base = sampleOffsets[first];
    last = static_cast<Id>(std::upper_bound(sampleOffsets.begin() + first + 1,
                             sampleOffsets.end(), base + BlockSamples) -
      sampleOffsets.begin() - 1);
    last = std::max(last, first + 1);
    if (projections.size() < static_cast<size_t>(sampleOffsets[last] - base))
    {
      projections.resize(static_cast<size_t>(sampleOffsets[last] - base));
    }
    vtkSMPTools::For(first, last, [&](Id begin, Id end) {
      ProjectionFrame frames[MaximumValence];
      for (Id p = begin; p < end; ++p)
      {
        this->ProjectSamples(level, around, p, samples.data() + sampleOffsets[p],
          sampleOffsets[p + 1] - sampleOffsets[p], areaUnit, frames,
          projections.data() + (sampleOffsets[p] - base), pointDistance[p]);
      }
    });
    for (Id s = sampleOffsets[first]; s < sampleOffsets[last]; ++s)
    {
      const Projection& projection = projections[s - base];
      if (projection.Triangle == InvalidId)
      {
        continue;
      }
      const double area = projection.Area;
      const double b = projection.B, c = projection.C;
      const double weights[3] = { std::max(0.0, 1.0 - b - c), b, c };
      const Id* tri = level.Triangle(projection.Triangle);
      for (int k = 0; k < 3; ++k)
      {
        PointSums& sum = sums[tri[k]];
        sum.Weighted += weights[k] * area * projection.Distance;
        sum.Weight += weights[k] * area;
        sum.OnSurface +=
          projection.Distance == 0.0f ? static_cast<float>(weights[k] * area) : 0.0f;
        sum.Samples += static_cast<float>(weights[k]);
        if (weights[k] >= NearWeight)
        {
          sum.Lowest = std::min(sum.Lowest, projection.Distance);
          sum.Highest = std::max(sum.Highest, projection.Distance);
        }
      }
    }
  }
}

// Point p's `count` samples projected into its triangles (`frames`: room for MaximumValence),
// each into the nearest triangle whose interior it projects into (a search that stops at one the
// sample lies on): where a fan bends sharply, a sample on one side also projects into the
// triangles of the other, at a distance, and counted there it moved the flat sides' points off
// a faceted input. Into `projections` (Triangle InvalidId where a sample projects into none),
// and the point's own distance to the input: to the plane of its nearest sample (in the
// plane's direction), along the plane's normal.
void LevelCentering::ProjectSamples(const TriangleMesh& level,
  const VertexTriangleAdjacency& around, Id p, const Id* samples, Id count, double areaUnit,
  ProjectionFrame* frames, Projection* projections, float& distance) const
{
  const Id triangles = around.Count(p);
  if (triangles > MaximumValence)
  {
    for (Id s = 0; s < count; ++s)
    {
      projections[s].Triangle = InvalidId;
    }
    return;
  }
  for (Id k = 0; k < triangles; ++k)
  {
    const Id* tri = level.Triangle(around.Of(p)[k]);
    frames[k].Set(level.Point(tri[0]), level.Point(tri[1]), level.Point(tri[2]));
  }
  double nearestSample = std::numeric_limits<double>::infinity();
  for (Id s = 0; s < count; ++s)
  {
    projections[s].Triangle = InvalidId;
    double x[3], unit[3], w[3];
    const double area = this->InputCentroid(samples[s], x, unit);
    Subtract(level.Point(p), x, w);
    const double across = Dot(w, unit);
    const double along = Dot(w, w) - across * across;
    if (along < nearestSample)
    {
      nearestSample = along;
      distance = static_cast<float>(-across);
    }
    double nearest = std::numeric_limits<double>::infinity();
    for (Id k = 0; k < triangles; ++k)
    {
      const ProjectionFrame& f = frames[k];
      if (!f.Valid)
      {
        continue;
      }
      Subtract(x, f.Corner, w);
      const double lb = Dot(w, f.B);
      const double lc = Dot(w, f.C);
      if (lb < -InsideTolerance || lc < -InsideTolerance || lb + lc > 1.0 + InsideTolerance)
      {
        continue;
      }
      const double d = Dot(w, f.Unit);
      if (!(std::abs(d) < nearest))
      {
        continue;
      }
      nearest = std::abs(d);
      const bool on = std::abs(d) <= OnSurface * f.Size;
      projections[s] = Projection{ around.Of(p)[k], static_cast<float>(area * areaUnit),
        static_cast<float>(on ? 0.0 : d), static_cast<float>(std::max(0.0, lb)),
        static_cast<float>(std::max(0.0, lc)) };
      if (on)
      {
        break;
      }
    }
  }
}

// Point p's shift (x, y, z into `shift`, left as it is when none): along its normal by the
// weighted mean distance of `sum`, at most LargestShift of its shortest edge; `itself`: its own
// distance to the input. p is an interior point whose triangles close into one disc.
void LevelCentering::PointShift(const TriangleMesh& level, const VertexTriangleAdjacency& around,
  Id p, const PointSums& sum, double itself, float* shift)
{
  // (A closed disc has at most MaximumValence triangles.)
  const Id count = around.Count(p);
  double areas[MaximumValence][3];
  double normal[3] = { 0.0, 0.0, 0.0 };
  double shortest = std::numeric_limits<double>::infinity();
  for (Id k = 0; k < count; ++k)
  {
    const Id t = around.Of(p)[k];
    level.AreaVector(t, areas[k]);
    for (int c = 0; c < 3; ++c)
    {
      normal[c] += areas[k][c];
    }
    const Id* tri = level.Triangle(t);
    for (int c = 0; c < 3; ++c)
    {
      if (tri[c] != p)
      {
        shortest = std::min(shortest, Distance2(level.Point(p), level.Point(tri[c])));
      }
    }
  }
  const double length = std::sqrt(Dot(normal, normal));
  bool smooth = length > 0.0;
  for (Id k = 0; k < count && smooth; ++k)
  {
    smooth = Dot(areas[k], normal) >= SmoothCosine * std::sqrt(Dot(areas[k], areas[k])) * length;
  }
  shortest = std::sqrt(shortest);
  // The mean minimises the squared distances; the largest distance near the point (where
  // the surface moves with it) may not grow: on a surface whose curvature changes fast (a
  // rounded edge between flat faces) the mean alone moved the largest deviation up by a
  // sixth.
  // The same for the point's own distance to the input (at a convex corner the mean can ask
  // a point that stands out already to move further out).
  const double largest = std::max(std::abs(itself),
    std::max(-static_cast<double>(sum.Lowest), static_cast<double>(sum.Highest)));
  double delta = sum.Weighted / sum.Weight;
  delta = std::max(delta, std::max(static_cast<double>(sum.Highest), itself) - largest);
  delta = std::min(delta, std::min(static_cast<double>(sum.Lowest), itself) + largest);
  delta = std::max(-LargestShift * shortest, std::min(LargestShift * shortest, delta));
  if (!smooth || !(std::abs(delta) > OnSurface * shortest))
  {
    return;
  }
  for (int c = 0; c < 3; ++c)
  {
    shift[c] = static_cast<float>(delta * normal[c] / length);
  }
}

} // namespace meshlod
