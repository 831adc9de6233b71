// Collapsibility rules of the collapse engine on tiny hand-made meshes, with exact outcomes.
#include "Core/CollapseMesh.h"
#include "MeshLODInputMesh.h"
#include "MeshLODTestCheck.h"
#include "MeshLODTestMeshes.h"

#include "vtkCellArray.h"
#include "vtkMath.h"
#include "vtkPolyData.h"
#include "vtkTriangleFilter.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

namespace
{
using namespace meshlod;

struct Fixture
{
  InputMesh Input;
  CollapseMesh State;
  CollapseRules Rules;
  Star Stars;

  explicit Fixture(vtkPolyData* poly)
  {
    vtkNew<vtkTriangleFilter> caller;
    ReadInputMesh(poly, caller, this->Input);
    this->State.Initialize(TriangleMesh(this->Input.Mesh), TriangleTopology(this->Input.Topology), 1.0, 0.0);
  }

  Legality Check(std::vector<Id> members, const double x[3], bool withPlane = true)
  {
    if (!this->State.GatherStar(members.data(), static_cast<int>(members.size()), this->Stars))
    {
      return Legality::Illegal;
    }
    double normal[3];
    const Id* m = members.data();
    TriangleNormal(this->State.Mesh.Point(m[0]), this->State.Mesh.Point(m[1]),
      this->State.Mesh.Point(m[2 % members.size()]), normal);
    const double* plane = withPlane && members.size() == 3 ? normal : nullptr;
    return this->State.IsLegal(this->Stars, x, plane, this->Rules);
  }

  std::array<double, 3> Centroid(const std::vector<Id>& members) const
  {
    std::array<double, 3> c = { 0, 0, 0 };
    for (const Id v : members)
    {
      for (int i = 0; i < 3; ++i)
      {
        c[i] += this->State.Mesh.Point(v)[i] / members.size();
      }
    }
    return c;
  }
};

// One triangle collapse on an icosphere: the triangle and its three neighbours die, two of its
// three vertices disappear, every other triangle around them is re-indexed.
void TestOneCollapse()
{
  Fixture f(testing::MakeIcosphere(1));
  MESHLOD_CHECK_EQ(f.State.AliveTriangles, 80);
  const Id t = 0;
  const std::vector<Id> tri(f.State.Mesh.Triangle(t), f.State.Mesh.Triangle(t) + 3);
  const std::array<double, 3> x = f.Centroid(tri);
  MESHLOD_CHECK(f.Check(tri, x.data()) == Legality::Legal);
  MESHLOD_CHECK_EQ(f.Stars.Dying.size(), 4u);
  MESHLOD_CHECK_EQ(f.Stars.Apexes.size(), 3u);
  const std::size_t ring = f.Stars.Ring.size();
  const Id survivor = f.State.Apply(f.Stars, x.data());
  MESHLOD_CHECK_EQ(survivor, std::min({ tri[0], tri[1], tri[2] }));
  int around = 0;
  f.State.ForEachTriangle(survivor, [&](Id) { ++around; });
  MESHLOD_CHECK_EQ(static_cast<std::size_t>(around), ring);
  int alive = 0;
  for (Id s = 0; s < f.State.Mesh.GetNumberOfTriangles(); ++s)
  {
    alive += f.State.IsAlive(s) ? 1 : 0;
  }
  MESHLOD_CHECK_EQ(alive, 76);
  int survivors = 0;
  for (Id v = 0; v < f.State.Mesh.GetNumberOfPoints(); ++v)
  {
    survivors += f.State.Survivor[v] == v ? 1 : 0;
  }
  MESHLOD_CHECK_EQ(survivors, 40);
}

// A neighbour apex of valence 4 would drop to valence 3 (paper 000, condition 2): the triangle
// is refused; swapping the shared edge and collapsing the new triangle is fine.
void TestValenceFourApexNeedsSwap()
{
  // Flip one edge of an icosphere between a valence-5 and a valence-6 vertex: the valence-5
  // vertex drops to 4.
  vtkSmartPointer<vtkPolyData> sphere = testing::MakeIcosphere(1);
  Fixture probe(sphere);
  TriangleTopology& topo = probe.Input.Topology;
  TriangleMesh& mesh = probe.Input.Mesh;
  Id flipT = InvalidId;
  int flipK = -1;
  for (Id t = 0; t < mesh.GetNumberOfTriangles() && flipT == InvalidId; ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      if (topo.Valence(mesh, mesh.Triangle(t)[k]) == 5 &&
        topo.Valence(mesh, mesh.Triangle(t)[(k + 1) % 3]) == 6)
      {
        flipT = t;
        flipK = k;
        break;
      }
    }
  }
  MESHLOD_CHECK(flipT != InvalidId);
  const Id* tri = mesh.Triangle(flipT);
  const Id u = tri[flipK], w = tri[(flipK + 1) % 3], c = tri[(flipK + 2) % 3];
  const Id other = topo.EdgeNeighbors[3 * flipT + flipK];
  const Id* otri = mesh.Triangle(other);
  Id d = InvalidId;
  for (int k = 0; k < 3; ++k)
  {
    d = (otri[k] != u && otri[k] != w) ? otri[k] : d;
  }
  // (u, w, c) and (w, u, d) become (c, u, d) and (d, w, c).
  vtkNew<vtkCellArray> polys;
  for (Id t = 0; t < mesh.GetNumberOfTriangles(); ++t)
  {
    const Id* s = mesh.Triangle(t);
    vtkIdType ids[3] = { s[0], s[1], s[2] };
    if (t == flipT)
    {
      ids[0] = c, ids[1] = u, ids[2] = d;
    }
    else if (t == other)
    {
      ids[0] = d, ids[1] = w, ids[2] = c;
    }
    polys->InsertNextCell(3, ids);
  }
  sphere->SetPolys(polys);
  Fixture f(sphere);
  MESHLOD_CHECK_EQ(f.Input.Topology.Valence(f.Input.Mesh, u), 4);

  // A triangle whose edge neighbour has u as its apex.
  int refused = 0, swapped = 0;
  for (Id t = 0; t < f.State.Mesh.GetNumberOfTriangles(); ++t)
  {
    const Id* s = f.State.Mesh.Triangle(t);
    if (CornerOf(s, u) >= 0)
    {
      continue;
    }
    for (int k = 0; k < 3; ++k)
    {
      const Id nb = f.Input.Topology.EdgeNeighbors[3 * t + k];
      if (nb < 0 || CornerOf(f.State.Mesh.Triangle(nb), u) < 0)
      {
        continue;
      }
      const std::vector<Id> members(s, s + 3);
      const std::array<double, 3> x = f.Centroid(members);
      const Legality direct = f.Check(members, x.data());
      refused += direct == Legality::LowValenceApex ? 1 : 0;
      MESHLOD_CHECK(direct == Legality::LowValenceApex);
      MESHLOD_CHECK_EQ(f.Stars.BlockingApex, u);
      // After swapping edge (s[k], s[k+1]) to (s[k+2], u), collapse one of the two new
      // triangles (s[k+2], s[k], u) or (s[k+2], u, s[k+1]).
      for (const std::vector<Id>& path : { std::vector<Id>{ s[(k + 2) % 3], s[k], u },
             std::vector<Id>{ s[(k + 2) % 3], u, s[(k + 1) % 3] } })
      {
        const std::array<double, 3> y = f.Centroid(path);
        if (f.Check(path, y.data()) == Legality::Legal)
        {
          ++swapped;
          MESHLOD_CHECK_EQ(f.Stars.Dying.size(), 4u);
          break;
        }
      }
    }
  }
  MESHLOD_CHECK_GT(refused, 0);
  MESHLOD_CHECK_GT(swapped, 0);
}

// The stencil polygon must be star-shaped around the collapse point (paper 000, condition 3).
void TestStarShape()
{
  // 4x4 flat grid; triangle (6, 7, 12) of the square at (1, 1).
  Fixture f(testing::MakeGrid(4, 4));
  const std::vector<Id> tri = { 6, 7, 12 };
  const std::array<double, 3> centroid = f.Centroid(tri);
  MESHLOD_CHECK(f.Check(tri, centroid.data()) == Legality::Legal);
  // Seen from (3.4, 1.3, 0) the stencil polygon is not star-shaped: some new triangles would
  // face down. With the normal and facing tests off only the star rule refuses it; with the
  // star rule off too, only the facing rule (no triangle may face away from the original
  // surface it stands for).
  const double outside[3] = { 3.4, 1.3, 0.0 };
  f.Rules.MinimumNormalCosine = -1.0;
  f.Rules.KeepFacing = false;
  MESHLOD_CHECK(f.Check(tri, outside) == Legality::Illegal);
  f.Rules.RequireStarShaped = false;
  MESHLOD_CHECK(f.Check(tri, outside) == Legality::Legal);
  f.Rules.KeepFacing = true;
  MESHLOD_CHECK(f.Check(tri, outside) == Legality::Illegal);
  // The normal rule: lifting the point tilts the ring triangles.
  f.Rules.RequireStarShaped = true;
  f.Rules.MinimumNormalCosine = 0.5; // 60 degrees
  const double low[3] = { centroid[0], centroid[1], 0.3 };
  const double high[3] = { centroid[0], centroid[1], 3.0 };
  MESHLOD_CHECK(f.Check(tri, low) == Legality::Legal);
  MESHLOD_CHECK(f.Check(tri, high) == Legality::Illegal);
}

// A collapse point on the line of a ring edge, or on a ring vertex, makes a triangle without
// area: refused down to the flatness rounding gives (a sine of 1e-6), which once let a solve that
// put the point on a corner of a box's flat faces leave triangles of zero area in the levels.
void TestDegenerateRefused()
{
  Fixture f(testing::MakeGrid(4, 4));
  // Only the degeneracy test judges the geometry here.
  f.Rules.MinimumNormalCosine = -1.0;
  f.Rules.RequireStarShaped = false;
  f.Rules.KeepFacing = false;
  const std::vector<Id> edge = { 6, 7 };
  const std::array<double, 3> middle = f.Centroid(edge);
  MESHLOD_CHECK(f.Check(edge, middle.data(), false) == Legality::Legal);
  // The first ring triangle (member, u, w): points beyond u on the line from w, off it by
  // `off` times the edge's length.
  const Id* ring = f.State.Mesh.Triangle(f.Stars.Ring[0]);
  const int c = f.Stars.RingCorner[0];
  const double* u = f.State.Mesh.Point(ring[(c + 1) % 3]);
  const double* w = f.State.Mesh.Point(ring[(c + 2) % 3]);
  auto beyond = [&](double off) {
    const double along[3] = { u[0] - w[0], u[1] - w[1], 0.0 };
    const std::array<double, 3> x = { u[0] + 0.5 * along[0] - off * along[1],
      u[1] + 0.5 * along[1] + off * along[0], 0.0 };
    return f.Check(edge, x.data(), false);
  };
  MESHLOD_CHECK(beyond(0.0) == Legality::Illegal);
  MESHLOD_CHECK(beyond(1e-9) == Legality::Illegal);
  MESHLOD_CHECK(beyond(1e-8) == Legality::Illegal);
  MESHLOD_CHECK(beyond(1e-2) == Legality::Legal);
  MESHLOD_CHECK(beyond(-1e-2) == Legality::Legal);
  MESHLOD_CHECK(f.Check(edge, u, false) == Legality::Illegal);
}

// Merging two boundary vertices across the interior would pinch the surface; locked
// (non-manifold) vertices never merge.
void TestBoundaryAndLocks()
{
  Fixture strip(testing::MakeGrid(2, 1)); // points 0 1 2 / 3 4 5, all on the boundary
  const std::array<double, 3> middle = strip.Centroid({ 1, 4 });
  MESHLOD_CHECK(strip.Check({ 1, 4 }, middle.data(), false) == Legality::Illegal);
  const std::array<double, 3> along = strip.Centroid({ 0, 1 });
  MESHLOD_CHECK(strip.Check({ 0, 1 }, along.data(), false) == Legality::Legal);

  Fixture bowTie(testing::MakeBowTie());
  MESHLOD_CHECK(bowTie.State.IsLocked(0));
  const std::array<double, 3> x = bowTie.Centroid({ 0, 1 });
  MESHLOD_CHECK(bowTie.Check({ 0, 1 }, x.data(), false) == Legality::Illegal);

  // A tetrahedron cannot lose a triangle: it would fold onto itself.
  Fixture tetrahedron(testing::MakeTetrahedron());
  const std::array<double, 3> y = tetrahedron.Centroid({ 0, 1, 2 });
  MESHLOD_CHECK(tetrahedron.Check({ 0, 1, 2 }, y.data()) != Legality::Legal);
  const std::array<double, 3> z = tetrahedron.Centroid({ 0, 1 });
  MESHLOD_CHECK(tetrahedron.Check({ 0, 1 }, z.data(), false) != Legality::Legal);
}
// A 3x3 grid wrapped into a torus: every vertex has valence 6 and sees 6 of the 8 others, so
// the endpoints of an edge share neighbours besides its two apexes. Merging them would create
// a non-manifold edge: the link condition must refuse every edge and triangle collapse, even
// though every apex keeps a valence of 5.
void TestLinkCondition()
{
  std::vector<double> points;
  std::vector<long long> triangles;
  for (int j = 0; j < 3; ++j)
  {
    for (int i = 0; i < 3; ++i)
    {
      const double u = 2.0 * vtkMath::Pi() * i / 3.0, v = 2.0 * vtkMath::Pi() * j / 3.0;
      points.insert(points.end(),
        { (2.0 + std::cos(v)) * std::cos(u), (2.0 + std::cos(v)) * std::sin(u), std::sin(v) });
      const long long a = j * 3 + i, b = j * 3 + (i + 1) % 3, c = ((j + 1) % 3) * 3 + (i + 1) % 3,
                      d = ((j + 1) % 3) * 3 + i;
      triangles.insert(triangles.end(), { a, b, c, a, c, d });
    }
  }
  Fixture f(testing::MakePolyData(points, triangles));
  MESHLOD_CHECK_EQ(f.Input.Topology.EulerCharacteristic(f.Input.Mesh), 0);
  f.Rules.MinimumNormalCosine = -1.0; // geometry aside: only topology decides here
  f.Rules.RequireStarShaped = false;
  int refused = 0;
  for (Id t = 0; t < f.State.Mesh.GetNumberOfTriangles(); ++t)
  {
    const Id* s = f.State.Mesh.Triangle(t);
    const std::vector<Id> tri(s, s + 3);
    const std::array<double, 3> x = f.Centroid(tri);
    MESHLOD_CHECK(f.Check(tri, x.data()) == Legality::Illegal);
    for (int k = 0; k < 3; ++k)
    {
      const std::vector<Id> edge = { s[k], s[(k + 1) % 3] };
      const std::array<double, 3> y = f.Centroid(edge);
      refused += f.Check(edge, y.data(), false) == Legality::Illegal ? 1 : 0;
    }
  }
  MESHLOD_CHECK_EQ(refused, 3 * 18);
}

// The distinct neighbours of every vertex of a fresh mesh, counted over all of its triangles.
std::vector<int> CountNeighbours(const TriangleMesh& mesh)
{
  std::vector<std::vector<Id>> around(mesh.GetNumberOfPoints());
  for (Id t = 0; t < mesh.GetNumberOfTriangles(); ++t)
  {
    const Id* tri = mesh.Triangle(t);
    for (int k = 0; k < 3; ++k)
    {
      around[tri[k]].push_back(tri[(k + 1) % 3]);
      around[tri[k]].push_back(tri[(k + 2) % 3]);
    }
  }
  std::vector<int> counts;
  for (std::vector<Id>& neighbours : around)
  {
    std::sort(neighbours.begin(), neighbours.end());
    counts.push_back(static_cast<int>(
      std::unique(neighbours.begin(), neighbours.end()) - neighbours.begin()));
  }
  return counts;
}

// Meshes with vertices of every kind the apex rule meets: locked (spindles sharing their apex,
// a bow tie), on a curve where three sheets meet (a sphere and its equatorial disk), on a
// boundary, and manifold inside.
std::vector<vtkSmartPointer<vtkPolyData>> MeshesOfEveryVertexKind()
{
  return { testing::MakeSphereWithEquatorialDisk(8, 5, 2), testing::MakeConesSharingApex(6, 5),
    testing::MakeBowTie(), testing::MakeGrid(3, 3), testing::MakeIcosphere(1) };
}

// HasValenceAtLeast reads a manifold vertex's triangle count, and walks the triangles of a
// locked or curve vertex counting distinct neighbours until it has enough: both against a
// count over every triangle, at the count and one above it.
void TestValenceCounts()
{
  int wrong = 0, locked = 0, curve = 0, boundary = 0;
  for (const vtkSmartPointer<vtkPolyData>& mesh : MeshesOfEveryVertexKind())
  {
    Fixture f(mesh);
    const std::vector<int> counts = CountNeighbours(f.State.Mesh);
    std::vector<Id> scratch;
    for (Id v = 0; v < f.State.Mesh.GetNumberOfPoints(); ++v)
    {
      wrong += f.State.HasValenceAtLeast(v, counts[v], scratch) ? 0 : 1;
      wrong += f.State.HasValenceAtLeast(v, counts[v] + 1, scratch) ? 1 : 0;
      locked += f.State.IsLocked(v) ? 1 : 0;
      curve += f.State.IsCurve(v) ? 1 : 0;
      boundary += f.State.IsBoundary(v) ? 1 : 0;
    }
  }
  MESHLOD_CHECK_EQ(wrong, 0);
  MESHLOD_CHECK_EQ(locked, 2); // the spindles' apex and the bow tie's centre
  MESHLOD_CHECK_EQ(curve, 8);  // the equator
  MESHLOD_CHECK_GT(boundary, 12);
}

// ApexValences against the rule as stated, on random lists of apexes drawn with repeats from
// vertices of every kind: the first apex of the list that has fewer distinct neighbours than
// 2 (on a boundary), 4 or 3 (with or without the valence-3 rule for the collapse's kind), plus
// the m entries naming it, blocks. A list of more than 8 apexes (thousands of sheets meeting
// at one edge) takes a sorted path of its own: both lengths must follow the rule, passing and
// blocking alike.
void TestApexRule()
{
  std::mt19937 random(5);
  std::array<int, 4> seen = { 0, 0, 0, 0 }; // short passed, short blocked, long ...
  int wrong = 0;
  for (const vtkSmartPointer<vtkPolyData>& mesh : MeshesOfEveryVertexKind())
  {
    Fixture f(mesh);
    const std::vector<int> counts = CountNeighbours(f.State.Mesh);
    const Id points = f.State.Mesh.GetNumberOfPoints();
    Star& star = f.Stars;
    for (int trial = 0; trial < 3000; ++trial)
    {
      std::vector<Id> pool(1 + random() % 32);
      for (Id& p : pool)
      {
        p = static_cast<Id>(random() % points);
      }
      star.Apexes.resize(1 + random() % 24);
      for (Id& p : star.Apexes)
      {
        p = pool[random() % pool.size()];
      }
      star.MemberCount = 2 + static_cast<int>(random() % 2);
      f.Rules.ForbidValenceThree = random() % 2 == 0;
      f.Rules.ForbidValenceThreeForEdges = random() % 2 == 0;
      const bool forbid =
        star.MemberCount == 3 ? f.Rules.ForbidValenceThree : f.Rules.ForbidValenceThreeForEdges;
      Id expected = InvalidId;
      for (const Id p : star.Apexes)
      {
        const int m = static_cast<int>(std::count(star.Apexes.begin(), star.Apexes.end(), p));
        const int minimum = f.State.IsBoundary(p) ? 2 : (forbid ? 4 : 3);
        if (counts[p] < minimum + m)
        {
          expected = p;
          break;
        }
      }
      star.BlockingApex = InvalidId;
      const Legality verdict = f.State.ApexValences(star, f.Rules);
      const bool blocked = verdict == Legality::LowValenceApex;
      const bool right = blocked ? star.BlockingApex == expected
                                 : verdict == Legality::Legal && expected == InvalidId;
      wrong += right ? 0 : 1;
      ++seen[(star.Apexes.size() > 8 ? 2 : 0) + (blocked ? 1 : 0)];
    }
  }
  MESHLOD_CHECK_EQ(wrong, 0);
  for (const int n : seen)
  {
    MESHLOD_CHECK_GE(n, 500);
  }
}
} // namespace

int TestTriangleCollapseRules(int, char*[])
{
  TestOneCollapse();
  TestValenceFourApexNeedsSwap();
  TestStarShape();
  TestBoundaryAndLocks();
  TestDegenerateRefused();
  TestLinkCondition();
  TestValenceCounts();
  TestApexRule();
  return meshlod::testing::Result();
}
