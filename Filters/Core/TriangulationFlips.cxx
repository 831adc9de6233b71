#include "TriangulationFlips.h"
#include "Vector3.h"

#include "vtkMath.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <utility>

namespace meshlod
{
namespace
{
// Closest points on the input surface by a walk: first over vertices (to the one nearest p, by
// point distances only), then over the triangles around the current triangle's corners to
// whichever is closer, until none is. Local (a walk, not a search), so its start must be near:
// a vertex of the cluster being judged, then the previous sample's vertex. `Surface` is a
// TypedLevelZeroView.
template <typename Surface>
struct SurfaceWalk
{
  Surface Mesh;
  const VertexTriangleAdjacency& Adjacency;
  static constexpr int MaximumSteps = 256;

  double Distance2To(Id t, const double p[3], double q[3], bool& inside) const
  {
    double corner[3][3];
    for (int k = 0; k < 3; ++k)
    {
      this->Mesh.Point(this->Mesh.Corner(t, k), corner[k]);
    }
    return ClosestPointOnTriangle(p, corner[0], corner[1], corner[2], q, inside);
  }

  double Distance2ToPoint(Id v, const double p[3]) const
  {
    double x[3];
    this->Mesh.Point(v, x);
    return Distance2(p, x);
  }

  // `vertex`: the start, then the vertex nearest p found.
  void Closest(const double p[3], Id& vertex, double q[3]) const
  {
    double nearest = this->Distance2ToPoint(vertex, p);
    for (int step = 0; step < MaximumSteps; ++step)
    {
      const Id current = vertex;
      for (Id i = this->Adjacency.Begin(current); i < this->Adjacency.End(current); ++i)
      {
        for (int k = 0; k < 3; ++k)
        {
          const Id corner = this->Mesh.Corner(this->Adjacency.Triangles[i], k);
          const double d = this->Distance2ToPoint(corner, p);
          if (d < nearest)
          {
            nearest = d;
            vertex = corner;
          }
        }
      }
      if (vertex == current)
      {
        break;
      }
    }
    Id triangle = InvalidId;
    double best = std::numeric_limits<double>::infinity();
    bool inside = false;
    for (Id i = this->Adjacency.Begin(vertex); i < this->Adjacency.End(vertex); ++i)
    {
      double x[3];
      bool in;
      const double d = this->Distance2To(this->Adjacency.Triangles[i], p, x, in);
      if (d < best)
      {
        best = d;
        inside = in;
        triangle = this->Adjacency.Triangles[i];
        std::copy_n(x, 3, q);
      }
    }
    // A closest point inside a triangle of the nearest vertex's fan is taken as it is; one on
    // the fan's rim may lie closer beyond it.
    for (int step = 0; step < MaximumSteps && !inside; ++step)
    {
      const Id current = triangle;
      for (int k = 0; k < 3; ++k)
      {
        const Id corner = this->Mesh.Corner(current, k);
        if (corner == vertex)
        {
          continue; // its fan was scanned
        }
        for (Id i = this->Adjacency.Begin(corner); i < this->Adjacency.End(corner); ++i)
        {
          const Id t = this->Adjacency.Triangles[i];
          double x[3];
          bool in;
          const double d = t == current ? best : this->Distance2To(t, p, x, in);
          if (d < best)
          {
            best = d;
            triangle = t;
            std::copy_n(x, 3, q);
          }
        }
      }
      if (triangle == current)
      {
        break;
      }
      vertex = InvalidId; // every corner of the new triangle is to be scanned
    }
    if (vertex == InvalidId)
    {
      vertex = this->Mesh.Corner(triangle, 0);
    }
  }
};

// The two configurations of a quad: the current triangles and the flipped ones.
struct Quad
{
  const double* Corner[2][2][3]; // [configuration][triangle][corner]

  double Distance2(int configuration, const double p[3]) const
  {
    double q[3];
    const auto& c = this->Corner[configuration];
    return std::min(ClosestPointOnTriangle(p, c[0][0], c[0][1], c[0][2], q),
      ClosestPointOnTriangle(p, c[1][0], c[1][1], c[1][2], q));
  }
};

template <typename Surface>
struct FlipJudge
{
  SurfaceWalk<Surface> Walk;
  const std::vector<Id>& StartVertex;
  double ErrorBound2;
  double MinimumSeparation2;

  // The local errors (squared) of the current and the flipped configuration, or false when the
  // flip is not possible. Edge (a, b) lies between (a, b, c) and (b, a, d).
  bool Judge(const TriangleMesh& level, Id a, Id b, Id c, Id d, double& before, double& after)
    const
  {
    const double* pa = level.Point(a);
    const double* pb = level.Point(b);
    const double* pc = level.Point(c);
    const double* pd = level.Point(d);
    if (!this->Unfolded(pa, pb, pc, pd) || !this->Bent(pa, pb, pc, pd))
    {
      return false;
    }
    const Id starts[4] = { this->StartVertex[a], this->StartVertex[b], this->StartVertex[c],
      this->StartVertex[d] };
    for (const Id v : starts)
    {
      if (v == InvalidId || this->Walk.Adjacency.Count(v) == 0)
      {
        return false;
      }
    }
    Id hint = starts[0];
    const Quad quad{ { { { pa, pb, pc }, { pb, pa, pd } }, { { pc, pa, pd }, { pd, pb, pc } } } };
    double error[2] = { 0.0, 0.0 };
    double sum[2] = { 0.0, 0.0 };
    // One sample p of configuration `own`: its distance to the input, and the distance of its
    // closest input point to either configuration.
    auto sample = [&](const double p[3], int own)
    {
      // The walk starts from the nearest of the previous sample's vertex and the corners'
      // start vertices: a walk by distance does not cross a ridge (on a tent, the midpoint of
      // the diagonal under the ridge stuck on the face it came from).
      double nearest = this->Walk.Distance2ToPoint(hint, p);
      for (const Id v : starts)
      {
        const double dv = this->Walk.Distance2ToPoint(v, p);
        if (dv < nearest)
        {
          nearest = dv;
          hint = v;
        }
      }
      double q[3];
      this->Walk.Closest(p, hint, q);
      const double d = Distance2(p, q);
      for (int y = 0; y < 2; ++y)
      {
        const double e = std::max(own == y ? d : 0.0, quad.Distance2(y, q));
        error[y] = std::max(error[y], e);
        sum[y] += e;
      }
    };
    // Each configuration's diagonal at its quarter points and midpoint, and its triangles'
    // centroids: where the two differ. (Adding the outer edges' midpoints, which both share, and
    // the points half way from the centroids to the corners made the flips take 1.7 times as
    // long on a 611k-triangle gyroid, for about the same error.)
    for (int x = 0; x < 2; ++x)
    {
      const double* u = x == 0 ? pa : pc;
      const double* v = x == 0 ? pb : pd;
      for (const double f : { 0.25, 0.5, 0.75 })
      {
        const double p[3] = { u[0] + f * (v[0] - u[0]), u[1] + f * (v[1] - u[1]),
          u[2] + f * (v[2] - u[2]) };
        sample(p, x);
      }
      for (const auto& tri : quad.Corner[x])
      {
        double centroid[3];
        for (int i = 0; i < 3; ++i)
        {
          centroid[i] = (tri[0][i] + tri[1][i] + tri[2][i]) / 3.0;
        }
        sample(centroid, x);
      }
    }
    before = error[0];
    after = sum[1] <= sum[0] ? error[1] : before; // a larger sum: no gain (see the header)
    // Nothing to gain at rounding level; beyond the level's error bound the walk went astray.
    return before > 1e-10 * Distance2(pa, pb) && before <= this->ErrorBound2;
  }

  // Whether the two configurations lie far enough apart for a flip to matter: the distance
  // between the lines of the two diagonals bounds how far a point of one configuration can lie
  // from the other.
  bool Bent(const double* pa, const double* pb, const double* pc, const double* pd) const
  {
    double ab[3], cd[3], ac[3], n[3];
    Subtract(pb, pa, ab);
    Subtract(pd, pc, cd);
    Subtract(pc, pa, ac);
    Cross(ab, cd, n);
    const double h = Dot(ac, n);
    return h * h >= this->MinimumSeparation2 * Dot(n, n);
  }

  // The flipped triangles stay within 60 degrees of the pair's summed normal, and bend against
  // each other no more than the current ones do or than about 70 degrees.
  static bool Unfolded(const double* pa, const double* pb, const double* pc, const double* pd)
  {
    double n1[3], n2[3], m1[3], m2[3];
    Normal(pa, pb, pc, n1);
    Normal(pb, pa, pd, n2);
    Normal(pc, pa, pd, m1);
    Normal(pd, pb, pc, m2);
    const double sum[3] = { n1[0] + n2[0], n1[1] + n2[1], n1[2] + n2[2] };
    const double ls = std::sqrt(Dot(sum, sum));
    const double k1 = std::sqrt(Dot(n1, n1));
    const double k2 = std::sqrt(Dot(n2, n2));
    const double l1 = std::sqrt(Dot(m1, m1));
    const double l2 = std::sqrt(Dot(m2, m2));
    if (!(ls > 0.0 && k1 > 0.0 && k2 > 0.0 && l1 > 0.0 && l2 > 0.0))
    {
      return false;
    }
    const double bend = std::min(0.3, Dot(n1, n2) / (k1 * k2));
    return Dot(m1, sum) >= 0.5 * l1 * ls && Dot(m2, sum) >= 0.5 * l2 * ls &&
      Dot(m1, m2) >= bend * l1 * l2;
  }
};

// The angle at corner o of triangle (o, x, y), in radians.
double CornerAngle(const double* o, const double* x, const double* y)
{
  double u[3], v[3], n[3];
  Subtract(x, o, u);
  Subtract(y, o, v);
  Cross(u, v, n);
  return std::atan2(std::sqrt(Dot(n, n)), Dot(u, v));
}

// The corner of `tri` that is neither a nor b, when tri holds the edge as (b, a); else InvalidId.
Id OppositeOfReversed(const Id* tri, Id a, Id b)
{
  for (int k = 0; k < 3; ++k)
  {
    if (tri[k] == b && tri[(k + 1) % 3] == a)
    {
      return tri[(k + 2) % 3];
    }
  }
  return InvalidId;
}

bool HasEdge(const TriangleMesh& level, const VertexTriangleAdjacency& adjacency, Id c, Id d)
{
  for (Id i = adjacency.Begin(c); i < adjacency.End(c); ++i)
  {
    if (CornerOf(level.Triangle(adjacency.Triangles[i]), d) >= 0)
    {
      return true;
    }
  }
  return false;
}
} // namespace

namespace
{
// A triangle's closest point comes from region tests when the squared sine of its largest
// angle is at least WellShapedSine2 (the angle up to about 174 degrees) and its shortest edge
// at least a hundredth of its longest. Their rounding errors grow like 1e-16 over that squared
// sine (4e-12 at a sine of 0.1 with coordinates near 10) and with the ratio of the longest edge
// to the shortest (1.4e-13 of the longest at 100, 2e-7 at 1e8, NaN where two corners nearly
// coincide). Other triangles take the slower, exact path of ClosestPointOnTriangle.
constexpr double WellShapedSine2 = 1e-2;
constexpr double WellShapedEdgeRatio2 = 1e-4;
// Below this squared sine between two edges, their cross product is computed accurately.
constexpr double ThinSine2 = 1e-6;

// a * b - c * d to within a unit in the last place.
double DifferenceOfProducts(double a, double b, double c, double d)
{
  const double cd = c * d;
  const double error = std::fma(-c, d, cd); // cd - c * d, exactly
  return std::fma(a, b, -cd) + error;
}

void AccurateCross(const double u[3], const double v[3], double out[3])
{
  out[0] = DifferenceOfProducts(u[1], v[2], u[2], v[1]);
  out[1] = DifferenceOfProducts(u[2], v[0], u[0], v[2]);
  out[2] = DifferenceOfProducts(u[0], v[1], u[1], v[0]);
}

// Ericson's region tests (Real-Time Collision Detection, 5.1.5) on the triangle with corner a
// and edges ab, ac from it: which feature (corner, edge or face) is closest follows from the
// signs of dot products of p's offsets with the edge vectors.
double RegionClosestPoint(const double p[3], const double a[3], const double ab[3],
  const double ac[3], double closest[3], bool& inside)
{
  inside = false;
  auto at = [&](const double* origin, const double* direction, double t) {
    for (int i = 0; i < 3; ++i)
    {
      closest[i] = origin[i] + t * direction[i];
    }
    return Distance2(p, closest);
  };
  double ap[3], bp[3], cp[3];
  Subtract(p, a, ap);
  const double d1 = Dot(ab, ap), d2 = Dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0)
  {
    return at(a, ab, 0.0);
  }
  Subtract(ap, ab, bp);
  const double d3 = Dot(ab, bp), d4 = Dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3)
  {
    return at(a, ab, 1.0);
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0)
  {
    return at(a, ab, d1 / (d1 - d3));
  }
  Subtract(ap, ac, cp);
  const double d5 = Dot(ab, cp), d6 = Dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6)
  {
    return at(a, ac, 1.0);
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0)
  {
    return at(a, ac, d2 / (d2 - d6));
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0)
  {
    double b[3], bc[3];
    for (int i = 0; i < 3; ++i)
    {
      b[i] = a[i] + ab[i];
    }
    Subtract(ac, ab, bc);
    return at(b, bc, (d4 - d3) / ((d4 - d3) + (d5 - d6)));
  }
  inside = true;
  const double total = va + vb + vc;
  const double v = vb / total, w = vc / total;
  for (int i = 0; i < 3; ++i)
  {
    closest[i] = a[i] + v * ab[i] + w * ac[i];
  }
  return Distance2(p, closest);
}

// What ClosestPointOnTriangle needs to know of a triangle's shape before measuring: its edges,
// the corner facing the longest edge (the largest angle: from there the cross product of the
// edges, and the region tests, are the most accurate; corner o lies between Edge[o - 1] and
// Edge[o], and the winding stays that of (b - a) x (c - a)), and whether the region tests may
// measure it.
struct TriangleShape
{
  const double* Corner[3];
  double Edge[3][3], Length2[3];
  int Longest = 0, Shortest = 0, Origin = 0;
  double Back[3], Normal[3]; // Back: from the origin to the corner before it
  double Normal2, Sides2;

  TriangleShape(const double a[3], const double b[3], const double c[3])
    : Corner{ a, b, c }
  {
    for (int k = 0; k < 3; ++k)
    {
      Subtract(this->Corner[(k + 1) % 3], this->Corner[k], this->Edge[k]);
      this->Length2[k] = Dot(this->Edge[k], this->Edge[k]);
      this->Longest = this->Length2[k] > this->Length2[this->Longest] ? k : this->Longest;
      this->Shortest = this->Length2[k] < this->Length2[this->Shortest] ? k : this->Shortest;
    }
    this->Origin = (this->Longest + 2) % 3;
    Subtract(this->Corner[(this->Origin + 2) % 3], this->Corner[this->Origin], this->Back);
    Cross(this->Edge[this->Origin], this->Back, this->Normal);
    this->Normal2 = Dot(this->Normal, this->Normal);
    this->Sides2 = this->Length2[this->Origin] * Dot(this->Back, this->Back);
  }
  bool IsWellShaped() const
  {
    return this->Normal2 > 0.0 && this->Normal2 >= WellShapedSine2 * this->Sides2 &&
      this->Length2[this->Shortest] >= WellShapedEdgeRatio2 * this->Length2[this->Longest];
  }
};
} // namespace

//------------------------------------------------------------------------------
double ClosestPointOnTriangle(
  const double p[3], const double a[3], const double b[3], const double c[3], double closest[3])
{
  bool inside;
  return ClosestPointOnTriangle(p, a, b, c, closest, inside);
}

int ClosestPointCorner(const double a[3], const double b[3], const double c[3])
{
  const TriangleShape shape(a, b, c);
  return shape.IsWellShaped() ? shape.Origin : -1;
}

double ClosestPointFromCorner(const double p[3],
  const double a[3],
  const double b[3],
  const double c[3],
  int corner,
  double closest[3])
{
  const double* corners[3] = { a, b, c };
  const double* origin = corners[corner];
  double edge[3], back[3];
  Subtract(corners[(corner + 1) % 3], origin, edge);
  Subtract(corners[(corner + 2) % 3], origin, back);
  bool inside;
  return RegionClosestPoint(p, origin, edge, back, closest, inside);
}

double ClosestPointOnTriangle(const double p[3],
  const double a[3],
  const double b[3],
  const double c[3],
  double closest[3],
  bool& inside)
{
  TriangleShape shape(a, b, c);
  if (shape.IsWellShaped())
  {
    return RegionClosestPoint(
      p, shape.Corner[shape.Origin], shape.Edge[shape.Origin], shape.Back, closest, inside);
  }
  const double* const* corner = shape.Corner;
  const auto& edge = shape.Edge;
  const auto& length2 = shape.Length2;
  const int longest = shape.Longest, o = shape.Origin;
  double* normal = shape.Normal;
  double normal2 = shape.Normal2;
  const double sides2 = shape.Sides2;
  const double* back = shape.Back;
  // A thin cap (every angle near 0 or 180 degrees) or a needle (an edge far shorter than the
  // others, as between nearly coincident corners): the region tests take barycentric
  // coordinates from differences of nearly equal products, which rounding spoils (on a triangle
  // 3.3 long and 3.3e-8 high, a point lying on it came out 2.5 units away), and divide 0 by 0
  // where two corners coincide. Here: the projection on the plane where it falls inside, else
  // the nearest of the closest points on the three edges.
  if (normal2 < ThinSine2 * sides2)
  {
    // The cross product's rounding, about 1e-16 of the product of the edges' lengths, would
    // tilt the normal by 1e-16 over the sine: each component again as a difference of two
    // products to within a unit in the last place (Kahan's algorithm, fused multiply-adds).
    AccurateCross(edge[o], back, normal);
    normal2 = Dot(normal, normal);
  }
  // Below a sine of 1e-10 the triangle is a segment (or a point) to within rounding: its edges
  // alone are exact to within its height.
  double offset[3][3]; // p - corner[k]
  for (int k = 0; k < 3; ++k)
  {
    Subtract(p, corner[k], offset[k]);
  }
  inside = normal2 > 1e-20 * sides2;
  for (int k = 0; k < 3 && inside; ++k)
  {
    double side[3];
    Cross(edge[k], offset[k], side);
    inside = Dot(side, normal) > 0.0;
  }
  if (inside)
  {
    // Beyond a tip sharper than rounding resolves, a point can pass the side tests; but the
    // triangle lies within the span of its longest edge (both angles at that edge are acute),
    // and such a point does not.
    const double along = Dot(offset[longest], edge[longest]);
    inside = along >= 0.0 && along <= length2[longest];
  }
  if (inside)
  {
    const double height = Dot(offset[o], normal) / normal2;
    for (int i = 0; i < 3; ++i)
    {
      closest[i] = p[i] - height * normal[i];
    }
    return height * height * normal2;
  }
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k)
  {
    double x[3];
    const double t =
      length2[k] > 0.0 ? std::max(0.0, std::min(1.0, Dot(offset[k], edge[k]) / length2[k])) : 0.0;
    for (int i = 0; i < 3; ++i)
    {
      x[i] = corner[k][i] + t * edge[k][i];
    }
    const double d2 = Distance2(p, x);
    if (d2 < best)
    {
      best = d2;
      std::copy_n(x, 3, closest);
    }
  }
  return best;
}

//------------------------------------------------------------------------------
namespace
{
// Each interior edge once, from its triangle of lower id: into `gain`, after / before where the
// flip is worth making, else -1. Only the edges of triangles marked `changed` are judged again
// (candidates left by a sweep that skipped them for a shared vertex keep their gain).
template <typename Judge>
void JudgeEdges(const TriangleMesh& level, const TriangleTopology& topology,
  const Judge& judge, const TriangulationFlipOptions& options,
  const std::vector<std::uint8_t>& changed, std::vector<float>& gain)
{
  const double minimumOpposite = options.MinimumOppositeAngles * (vtkMath::Pi() / 180.0);
  vtkSMPTools::For(0,
    level.GetNumberOfTriangles(),
    [&](Id begin, Id end)
    {
      for (Id t = begin; t < end; ++t)
      {
        const Id* tri = level.Triangle(t);
        for (int k = 0; k < 3; ++k)
        {
          float& g = gain[3 * static_cast<size_t>(t) + k];
          const Id u = topology.EdgeNeighbors[3 * static_cast<size_t>(t) + k];
          if (u <= t)
          {
            g = -1.0f; // boundary, non-manifold, or judged from u
            continue;
          }
          if (!changed[t] && !changed[u])
          {
            continue; // the same quad as in the sweep before
          }
          g = -1.0f;
          const Id a = tri[k], b = tri[(k + 1) % 3], c = tri[(k + 2) % 3];
          const Id d = OppositeOfReversed(level.Triangle(u), a, b);
          // (A quad whose corners off the edge are sharp needs no judging, see the header.)
          double before, after;
          if (d != InvalidId && d != c &&
            CornerAngle(level.Point(c), level.Point(a), level.Point(b)) +
                CornerAngle(level.Point(d), level.Point(b), level.Point(a)) >=
              minimumOpposite &&
            judge.Judge(level, a, b, c, d, before, after) &&
            after <= options.RequiredGain * before)
          {
            g = static_cast<float>(after / before);
          }
        }
      }
    });
}

// How many triangles of a level have each image in the next level (TriangulationFlipOptions::
// NextTarget): a flat open-addressing table of sorted point triples, degenerate images (which
// vanish) left out.
class ImageCounts
{
public:
  using Key = std::array<Id, 3>;

  ImageCounts(const TriangleMesh& level, const Id* nextTarget)
    : NextTarget(nextTarget)
  {
    this->Resize(2 * static_cast<size_t>(level.GetNumberOfTriangles()) + 16);
    for (Id t = 0; t < level.GetNumberOfTriangles(); ++t)
    {
      this->Add(level.Triangle(t), 1);
    }
  }
  // The image of triangle `corners`; false when it is degenerate.
  bool Image(const Id* corners, Key& key) const
  {
    for (int i = 0; i < 3; ++i)
    {
      key[i] = this->NextTarget[corners[i]];
    }
    std::sort(key.begin(), key.end());
    return key[0] != key[1] && key[1] != key[2];
  }
  int Count(const Key& key) const { return this->Slots[this->Find(key)].Count; }
  void Add(const Id* corners, int delta)
  {
    Key key;
    if (!this->Image(corners, key))
    {
      return;
    }
    Slot* slot = &this->Slots[this->Find(key)];
    if (slot->Triple[0] == InvalidId)
    {
      if (2 * (this->Used + 1) > this->Slots.size())
      {
        this->Resize(2 * this->Slots.size());
        slot = &this->Slots[this->Find(key)];
      }
      slot->Triple = key;
      ++this->Used;
    }
    slot->Count += delta;
  }

private:
  struct Slot
  {
    Key Triple{ { InvalidId, InvalidId, InvalidId } };
    int Count = 0;
  };
  // The slot holding `key`, or the empty one where it would go.
  size_t Find(const Key& key) const
  {
    const size_t mask = this->Slots.size() - 1;
    size_t i = (static_cast<size_t>(key[0]) * 0x9e3779b97f4a7c15ull ^
                 static_cast<size_t>(key[1]) * 0xc2b2ae3d27d4eb4full ^
                 static_cast<size_t>(key[2]) * 0x165667b19e3779f9ull) >>
      17;
    for (i &= mask; this->Slots[i].Triple[0] != InvalidId && this->Slots[i].Triple != key;
         i = (i + 1) & mask)
    {
    }
    return i;
  }
  void Resize(size_t atLeast)
  {
    size_t size = 16;
    while (size < atLeast)
    {
      size *= 2;
    }
    std::vector<Slot> old(size);
    old.swap(this->Slots);
    for (const Slot& slot : old)
    {
      if (slot.Triple[0] != InvalidId)
      {
        this->Slots[this->Find(slot.Triple)] = slot;
      }
    }
  }

  const Id* NextTarget;
  std::vector<Slot> Slots;
  size_t Used = 0;
};

// Whether replacing triangles `t` and `u` by `made` (two triangles) gives a triangle the image
// of another one (see ImageCounts).
bool FlipDoublesImage(const ImageCounts& images, const Id* t, const Id* u, const Id made[2][3])
{
  ImageCounts::Key mine[2], before[2];
  const bool had[2] = { images.Image(t, before[0]), images.Image(u, before[1]) };
  const bool has[2] = { images.Image(made[0], mine[0]), images.Image(made[1], mine[1]) };
  if (has[0] && has[1] && mine[0] == mine[1])
  {
    return true;
  }
  for (int i = 0; i < 2; ++i)
  {
    if (has[i])
    {
      int others = images.Count(mine[i]);
      others -= (had[0] && before[0] == mine[i]) ? 1 : 0;
      others -= (had[1] && before[1] == mine[i]) ? 1 : 0;
      if (others > 0)
      {
        return true;
      }
    }
  }
  return false;
}

// The flips judged worth making, best gain first, at most one per vertex and sweep: the
// triangles around an untouched vertex are as they were judged, so is every edge test below.
// The triangles flipped are marked in `changedNext` (and listed in `flipped`, when given). With
// `images`, a flip whose triangle would have the image of another is refused, and the counts
// follow the flips made. Returns the number of flips.
Id MakeFlips(TriangleMesh& level, const TriangleTopology& topology, std::vector<float>& gain,
  std::vector<std::uint8_t>& changedNext, std::vector<Id>* flipped, ImageCounts* images)
{
  std::vector<Id> candidates;
  for (Id e = 0; e < 3 * level.GetNumberOfTriangles(); ++e)
  {
    if (gain[e] >= 0.0f)
    {
      candidates.push_back(e);
    }
  }
  std::stable_sort(candidates.begin(),
    candidates.end(),
    [&](Id x, Id y) { return gain[x] < gain[y]; });
  std::vector<std::uint8_t> used(level.GetNumberOfPoints(), 0);
  Id made = 0;
  for (const Id e : candidates)
  {
    const Id t = e / 3;
    const int k = static_cast<int>(e % 3);
    Id* tri = level.Triangle(t);
    const Id u = topology.EdgeNeighbors[e];
    const Id a = tri[k], b = tri[(k + 1) % 3], c = tri[(k + 2) % 3];
    const Id d = OppositeOfReversed(level.Triangle(u), a, b);
    const Id after[2][3] = { { c, a, d }, { d, b, c } };
    if (d == InvalidId || used[a] || used[b] || used[c] || used[d] ||
      HasEdge(level, topology.VertexTriangles, c, d) ||
      (images != nullptr && FlipDoublesImage(*images, tri, level.Triangle(u), after)))
    {
      continue;
    }
    if (images != nullptr)
    {
      images->Add(tri, -1);
      images->Add(level.Triangle(u), -1);
      images->Add(after[0], 1);
      images->Add(after[1], 1);
    }
    std::copy_n(after[0], 3, tri);
    std::copy_n(after[1], 3, level.Triangle(u));
    used[a] = used[b] = used[c] = used[d] = 1;
    changedNext[t] = changedNext[u] = 1;
    if (flipped)
    {
      flipped->push_back(t);
      flipped->push_back(u);
    }
    gain[e] = -1.0f;
    ++made;
  }
  return made;
}

// Sweeps of judging and flipping until one flips nothing (at most MaximumSweeps).
template <typename Judge>
Id MakeSweeps(TriangleMesh& level, const Judge& judge, const TriangulationFlipOptions& options,
  std::vector<Id>* flipped)
{
  const Id nt = level.GetNumberOfTriangles();
  std::vector<float> gain(3 * static_cast<size_t>(nt), -1.0f);
  // A judgement depends on the quad's four points only: after the first sweep only the edges of
  // the triangles a flip changed are judged again.
  std::vector<std::uint8_t> changed(nt, 1), changedNext(nt, 0);
  std::unique_ptr<ImageCounts> images;
  if (options.NextTarget != nullptr)
  {
    images.reset(new ImageCounts(level, options.NextTarget));
  }
  Id flips = 0;
  for (int sweep = 0; sweep < options.MaximumSweeps; ++sweep)
  {
    TriangleTopology topology;
    topology.Build(level);
    JudgeEdges(level, topology, judge, options, changed, gain);
    std::fill(changedNext.begin(), changedNext.end(), 0);
    const Id made = MakeFlips(level, topology, gain, changedNext, flipped, images.get());
    flips += made;
    changed.swap(changedNext);
    if (made == 0)
    {
      break;
    }
  }
  return flips;
}
} // namespace

//------------------------------------------------------------------------------
Id ImproveTriangulation(const LevelZeroView& input,
  const VertexTriangleAdjacency& inputTriangles,
  const std::vector<Id>& startVertex,
  double errorBound,
  TriangleMesh& level,
  const TriangulationFlipOptions& options,
  std::vector<Id>* flipped)
{
  if (!(errorBound > 0.0) || !std::isfinite(errorBound))
  {
    return 0; // an exact level (or no bound): nothing to gain
  }
  Id flips = 0;
  input.Dispatch([&](auto surface) {
    using Surface = decltype(surface);
    const FlipJudge<Surface> judge{ SurfaceWalk<Surface>{ surface, inputTriangles }, startVertex,
      4.0 * errorBound * errorBound, std::pow(options.MinimumSeparation * errorBound, 2) };
    flips = MakeSweeps(level, judge, options, flipped);
  });
  return flips;
}

} // namespace meshlod
