// CollapseMesh (CollapseMesh.h): whether merging a star's members keeps a manifold mesh of the
// same topology with no flipped triangle (IsLegal and its parts: the merged vertex's link, a merge
// along a curve where sheets meet, the apexes' valences, the new triangles' shapes). The rest of
// CollapseMesh (its state, stars, pieces and the collapse itself) is in CollapseMesh.cxx.
#include "CollapseMesh.h"

#include "Vector3.h"

#include <algorithm>

namespace meshlod
{
namespace
{
// A new triangle is degenerate when the sine of its corner between the moved edge and the
// opposite edge is below 1e-6 (squared here). A collapse point landing on a neighbour (the
// solve puts it exactly on a corner of a box's flat faces) makes a sine at rounding level,
// which left triangles of zero area in the levels; one on the line of a ring edge (the solve
// is exact there to about 1e-9) made slivers with sines of 7e-9, flat in single precision.
constexpr double DegenerateSine2 = 1e-12;

// Whether two vectors with dot product `dot` and squared lengths' product `norms2` make an
// angle whose cosine is at least `cosine`.
bool WithinAngle(double dot, double norms2, double cosine)
{
  const double bound = cosine * cosine * norms2;
  return cosine >= 0.0 ? (dot >= 0.0 && dot * dot >= bound) : (dot >= 0.0 || dot * dot <= bound);
}

// The end of link edge {ends[2 edge], ends[2 edge + 1]} that is not v.
Id OtherEnd(const std::vector<Id>& ends, Id edge, Id v)
{
  return ends[2 * edge] == v ? ends[2 * edge + 1] : ends[2 * edge];
}

// The end of LinkIsSimple, once every vertex is known to be on one or two edges, each edge
// once: `pathEnds` vertices are on one edge (`start` one of them), and edgesOf(v) gives v's
// edges (the second InvalidId at a path end). A simple cycle has no path end, a simple path
// (boundary) two, and a walk from `start` (or round from ends[0]) passes every edge.
template <typename EdgesOf>
bool WalkCoversLink(
  const std::vector<Id>& ends, bool boundary, int pathEnds, Id start, EdgesOf&& edgesOf)
{
  if (pathEnds != (boundary ? 2 : 0))
  {
    return false;
  }
  const Id edges = static_cast<Id>(ends.size() / 2);
  const Id first = boundary ? start : ends[0];
  Id at = first, previous = InvalidId, walked = 0;
  for (;;)
  {
    const std::pair<Id, Id> around = edgesOf(at);
    const Id next = around.first != previous ? around.first : around.second;
    if (next == InvalidId)
    {
      break; // the far end of the path
    }
    at = OtherEnd(ends, next, at);
    previous = next;
    if (++walked > edges)
    {
      return false;
    }
    if (!boundary && at == first)
    {
      break; // round the cycle
    }
  }
  return walked == edges; // less: several cycles or paths, the merge would pinch the surface
}

// Whether the edges {ends[2 i], ends[2 i + 1]} form one simple cycle (or, for a boundary merge,
// one simple path) using each edge once: no vertex on more than two edges, no edge twice, and a
// walk from a path end (or any vertex of a cycle) that comes round through every edge. Each
// vertex's (at most two) edges go into a hash table, `table` (3 entries per slot: vertex, first
// edge, second edge), linear in the link's size: sorting the (vertex, edge) incidences instead
// cost n log n for every check next to a vertex of high valence (a closed cone with the
// independent sets: 3.4 s for 4,000 triangles, most of it sorting), and on the benchmark
// isosurfaces' links of a dozen edges the table took 1.2% fewer instructions of the whole run.
bool LinkIsSimple(const std::vector<Id>& ends, bool boundary, std::vector<Id>& table)
{
  if (!boundary && ends.size() < 6)
  {
    return false; // a cycle needs three edges
  }
  std::size_t slots = 16;
  while (slots < 2 * ends.size())
  {
    slots *= 2;
  }
  table.assign(3 * slots, InvalidId);
  // The slot of v: its own, or the empty one where it goes.
  const auto slotOf = [&](Id v) {
    std::size_t s = (static_cast<std::uint64_t>(v) * 0x9E3779B97F4A7C15ull >> 32) & (slots - 1);
    while (table[3 * s] != InvalidId && table[3 * s] != v)
    {
      s = (s + 1) & (slots - 1);
    }
    return 3 * s;
  };
  const auto other = [&](Id edge, Id v) { return OtherEnd(ends, edge, v); };
  for (std::size_t i = 0; i < ends.size(); ++i)
  {
    const std::size_t s = slotOf(ends[i]);
    const Id edge = static_cast<Id>(i / 2);
    if (table[s] == InvalidId)
    {
      table[s] = ends[i];
      table[s + 1] = edge;
    }
    else if (table[s + 2] != InvalidId || other(table[s + 1], ends[i]) == other(edge, ends[i]))
    {
      return false; // a vertex on three new triangles' far edges, or one edge twice
    }
    else
    {
      table[s + 2] = edge;
    }
  }
  Id start = InvalidId;
  int pathEnds = 0;
  for (std::size_t s = 0; s < table.size(); s += 3)
  {
    if (table[s] != InvalidId && table[s + 2] == InvalidId)
    {
      ++pathEnds;
      start = table[s];
    }
  }
  return WalkCoversLink(ends, boundary, pathEnds, start, [&](Id v) {
    const std::size_t s = slotOf(v);
    return std::make_pair(table[s + 1], table[s + 2]);
  });
}

} // namespace

//------------------------------------------------------------------------------
bool CollapseMesh::MergeKeepsLinks(const Star& star, bool alongCurve) const
{
  // (vertex, code) for every far corner of a ring triangle (code: the member's bit) and the
  // apex of every dying triangle with two members (code: their bits, shifted by 3).
  const auto bit = [&](Id v) {
    int b = 0;
    for (int m = 0; m < star.MemberCount; ++m)
    {
      b |= star.Members[m] == v ? 1 << m : 0;
    }
    return b;
  };
  std::vector<std::pair<Id, Id>>& seen = star.PairScratch;
  seen.clear();
  for (std::size_t i = 0; i < star.Ring.size(); ++i)
  {
    const Id* tri = this->Mesh.Triangle(star.Ring[i]);
    const int c = star.RingCorner[i];
    const int member = bit(tri[c]);
    seen.emplace_back(tri[(c + 1) % 3], member);
    seen.emplace_back(tri[(c + 2) % 3], member);
  }
  for (const Id d : star.Dying)
  {
    const Id* tri = this->Mesh.Triangle(d);
    const int mask = bit(tri[0]) | bit(tri[1]) | bit(tri[2]);
    for (int k = 0; k < 3; ++k)
    {
      if (bit(tri[k]) == 0)
      {
        seen.emplace_back(tri[k], mask << 3);
      }
    }
  }
  std::sort(seen.begin(), seen.end());
  for (std::size_t i = 0; i < seen.size();)
  {
    const Id p = seen[i].first;
    int joined = 0; // members joined to p
    int linked[3] = { 0, 0, 0 }; // per member, the members it shares a dying triangle at p with
    int triangles[3] = { 0, 0, 0 }; // on the edge from each member to p
    int dying = 0;
    for (; i < seen.size() && seen[i].first == p; ++i)
    {
      const int code = static_cast<int>(seen[i].second);
      const int members = code < 8 ? code : code >> 3;
      joined |= members;
      dying += code < 8 ? 0 : 1;
      for (int m = 0; m < 3; ++m)
      {
        triangles[m] += (members >> m) & 1;
        linked[m] |= code < 8 || !((members >> m) & 1) ? 0 : members;
      }
    }
    // The members joined to p must be connected through dying triangles at p (for two members:
    // one on both); else p would join the merged vertex twice over, a pinch.
    int reached = joined & -joined; // its lowest member
    for (int pass = 0; pass < 2; ++pass)
    {
      for (int m = 0; m < 3; ++m)
      {
        reached |= (reached >> m) & 1 ? linked[m] : 0;
      }
    }
    if (reached != joined)
    {
      return false;
    }
    // p's edges to the members become one edge, with their triangles less the dying ones (each
    // was on two of those edges). None left: p, a bow tie, would lose a wing (both its edges to
    // two members were boundary edges of the dying triangle alone).
    if (dying > 0 && triangles[0] + triangles[1] + triangles[2] - 2 * dying < 1)
    {
      return false;
    }
    if (alongCurve && triangles[0] > 2 && triangles[1] > 2)
    {
      return false; // the curve runs round the dying triangle: its two edges would become one
    }
  }
  // Two ring triangles of different members on the same far edge would become one triangle
  // twice.
  std::vector<std::pair<Id, Id>>& far = seen;
  far.clear();
  for (std::size_t i = 0; i < star.Ring.size(); ++i)
  {
    const Id* tri = this->Mesh.Triangle(star.Ring[i]);
    const int c = star.RingCorner[i];
    const Id u = tri[(c + 1) % 3], w = tri[(c + 2) % 3];
    far.emplace_back(std::min(u, w), std::max(u, w));
  }
  std::sort(far.begin(), far.end());
  return std::adjacent_find(far.begin(), far.end()) == far.end();
}

//------------------------------------------------------------------------------
bool CollapseMesh::CurveMergeIsValid(const Star& star) const
{
  // Two kinds of merge keep the sheets and the curves where they meet: along the curve (both
  // members on it, the edge between them one of its edges, with a triangle of each sheet on
  // it), and a sheet's inner vertex into a curve vertex across a manifold edge. Each then is a
  // boundary edge collapse or an inner one within every sheet involved, and the link condition
  // (MergeKeepsLinks: the members' common neighbours are only the apexes of the dying
  // triangles) makes it keep each sheet's topology and every other edge's triangle count: apex
  // p's edges to the two members become one edge with their counts added less the two of the
  // dying triangle.
  if (star.MemberCount != 2)
  {
    return false;
  }
  const Id a = star.Members[0], b = star.Members[1];
  if (this->IsBoundary(a) || this->IsBoundary(b))
  {
    return false;
  }
  const bool along = this->IsCurve(a) && this->IsCurve(b);
  if (along ? star.Dying.size() < 3 : star.Dying.size() != 2)
  {
    return false; // across a sheet between two curve points (a pinch), or not a manifold edge
  }
  return this->MergeKeepsLinks(star, along);
}

//------------------------------------------------------------------------------
Legality CollapseMesh::IsLegal(
  const Star& star, const double x[3], const double* planeNormal, const CollapseRules& rules) const
{
  star.BlockingApex = InvalidId;
  const std::size_t ringSize = star.Ring.size();
  if (ringSize == 0)
  {
    return Legality::Illegal;
  }
  bool boundary = false, curve = false;
  for (int m = 0; m < star.MemberCount; ++m)
  {
    boundary = boundary || this->IsBoundary(star.Members[m]);
    curve = curve || this->IsCurve(star.Members[m]);
  }
  if (curve && !this->CurveMergeIsValid(star))
  {
    return Legality::Illegal;
  }
  // The verdict is the first refusal in the order link, apexes, geometry (which one matters:
  // LowValenceApex leads to a swap). Around a vertex of high valence the link check sorts the
  // whole fan, while the geometry walks it once and refuses most of what is refused there (a
  // hub moved into its fan folds it over); there, where the apexes pass, the geometry goes
  // first, to the same verdicts. (A flat disc of 16,000 fan triangles inside two rings spent
  // more than half its time sorting links of collapses that folded.)
  if (ringSize > static_cast<std::size_t>(FanTriangleLimit))
  {
    const Legality apexes = this->ApexValences(star, rules);
    if (apexes == Legality::Legal && !this->GeometryKeepsShape(star, x, planeNormal, rules, curve))
    {
      return Legality::Illegal;
    }
    if (!this->LinkKeepsManifold(star, boundary, curve))
    {
      star.BlockingApex = InvalidId;
      return Legality::Illegal;
    }
    return apexes;
  }
  if (!this->LinkKeepsManifold(star, boundary, curve))
  {
    return Legality::Illegal;
  }
  const Legality apexes = this->ApexValences(star, rules);
  if (apexes != Legality::Legal)
  {
    return apexes;
  }
  return this->GeometryKeepsShape(star, x, planeNormal, rules, curve) ? Legality::Legal
                                                                     : Legality::Illegal;
}

//------------------------------------------------------------------------------
bool CollapseMesh::LinkKeepsManifold(const Star& star, bool boundary, bool curve) const
{
  const std::size_t ringSize = star.Ring.size();

  // Link of the merged vertex: ring triangle (member, u, w) contributes the edge {u, w}. A
  // manifold result needs these edges to form one simple cycle (interior) or one simple path
  // (boundary): no edge twice, every vertex on two edges (a path's two ends on one). The edges
  // are not directed: on a non-orientable surface (Boy's surface, a Moebius strip) neighbouring
  // triangles disagree on the direction of their shared edge somewhere, and a test of directed
  // edges refused every collapse along that seam.
  std::vector<Id>& ends = star.LinkScratch;
  ends.resize(2 * ringSize);
  std::uint8_t linkFlags = 0;
  for (std::size_t i = 0; i < ringSize; ++i)
  {
    const Id* tri = this->Mesh.Triangle(star.Ring[i]);
    const int c = star.RingCorner[i];
    ends[2 * i] = tri[(c + 1) % 3];
    ends[2 * i + 1] = tri[(c + 2) % 3];
    linkFlags |= this->Flags[ends[2 * i]] | this->Flags[ends[2 * i + 1]];
  }
  for (const Id p : star.Apexes)
  {
    linkFlags |= this->Flags[p];
  }
  if (!curve && !LinkIsSimple(ends, boundary, star.IdScratch))
  {
    return false;
  }
  // On a boundary or next to a non-manifold vertex one simple cycle or path of the link does
  // not show that the merge keeps the topology: a triangle collapse with two members on a
  // hole of three edges closed the hole (the members' other boundary gave the path its two
  // ends), and one with a dying triangle's apex where two boundary loops touch (a bow tie)
  // closed one of the loops. The link condition does.
  if (!curve && (boundary || (linkFlags & (FlagLocked | FlagCurve)) != 0) &&
    !this->MergeKeepsLinks(star, false))
  {
    return false;
  }

  return true;
}

//------------------------------------------------------------------------------
Legality CollapseMesh::ApexValences(const Star& star, const CollapseRules& rules) const
{
  // Paper 000's rule against new valence-3 vertices (see CollapseRules).
  const bool forbidValenceThree =
    star.MemberCount == 3 ? rules.ForbidValenceThree : rules.ForbidValenceThreeForEdges;
  // Apexes lose edges: an apex shared by m dying triangles was joined to m + 1 members, which
  // become one vertex, so it loses m edges. Its valence must stay healthy.
  const auto keepsValence = [&](Id p, int m) {
    const int minimum = this->IsBoundary(p) ? 2 : (forbidValenceThree ? 4 : 3);
    return this->HasValenceAtLeast(p, minimum + m, star.IdScratch);
  };
  const std::vector<Id>& apexes = star.Apexes;
  if (apexes.size() <= 8)
  {
    for (std::size_t i = 0; i < apexes.size(); ++i)
    {
      const Id p = apexes[i];
      if (std::find(apexes.begin(), apexes.begin() + i, p) != apexes.begin() + i)
      {
        continue; // counted at its first occurrence
      }
      if (!keepsValence(p, static_cast<int>(std::count(apexes.begin(), apexes.end(), p))))
      {
        star.BlockingApex = p;
        return Legality::LowValenceApex;
      }
    }
    return Legality::Legal;
  }
  // An edge on a curve where thousands of sheets meet has an apex per sheet: the same rule by
  // sorting (apex, place), which blocks on the apex that comes first in the list, as above.
  std::vector<std::pair<Id, Id>>& order = star.PairScratch;
  order.clear();
  for (std::size_t i = 0; i < apexes.size(); ++i)
  {
    order.emplace_back(apexes[i], static_cast<Id>(i));
  }
  std::sort(order.begin(), order.end());
  Id firstBlocked = InvalidId;
  for (std::size_t g = 0, next = 0; g < order.size(); g = next)
  {
    for (next = g + 1; next < order.size() && order[next].first == order[g].first; ++next)
    {
    }
    const bool earlier = firstBlocked == InvalidId || order[g].second < firstBlocked;
    if (earlier && !keepsValence(order[g].first, static_cast<int>(next - g)))
    {
      firstBlocked = order[g].second;
    }
  }
  if (firstBlocked == InvalidId)
  {
    return Legality::Legal;
  }
  star.BlockingApex = apexes[firstBlocked];
  return Legality::LowValenceApex;
}

//------------------------------------------------------------------------------
bool CollapseMesh::GeometryKeepsShape(const Star& star, const double x[3],
  const double* planeNormal, const CollapseRules& rules, bool curve) const
{
  const std::size_t ringSize = star.Ring.size();
  // Geometry: no ring triangle may flip or turn too far, and (paper 000) the stencil boundary
  // polygon must be star-shaped around the collapse point seen along the triangle's normal.
  // Normals stay unnormalised (twice the area); angles are compared through squares.
  double merged[3] = { 0, 0, 0 }; // the members' facing, which the merged vertex gets
  for (int m = 0; m < star.MemberCount; ++m)
  {
    const float* f = this->Facing.data() + 3 * static_cast<std::size_t>(star.Members[m]);
    merged[0] += f[0];
    merged[1] += f[1];
    merged[2] += f[2];
  }
  for (std::size_t i = 0; i < ringSize; ++i)
  {
    const Id* tri = this->Mesh.Triangle(star.Ring[i]);
    const int c = star.RingCorner[i];
    const double* u = this->Mesh.Point(tri[(c + 1) % 3]);
    const double* w = this->Mesh.Point(tri[(c + 2) % 3]);
    double uw[3], fromMember[3], fromX[3], before[3], after[3];
    Subtract(w, u, uw);
    Subtract(u, this->Mesh.Point(tri[c]), fromMember);
    Cross(fromMember, uw, before);
    Subtract(u, x, fromX);
    Cross(fromX, uw, after);
    const double after2 = Dot(after, after);
    const double before2 = Dot(before, before);
    const double uw2 = Dot(uw, uw);
    const double tiny = 1e-30 * uw2 * uw2;
    // Degenerate (cross2: the squared cross product of `side` and uw): the corner at u all but
    // flat (DegenerateSine2), or the area below 1e-15 of the squared edge (u, w).
    auto degenerate = [&](double cross2, const double side[3]) {
      return !(cross2 > std::max(tiny, DegenerateSine2 * Dot(side, side) * uw2));
    };
    if (degenerate(after2, fromX))
    {
      if (!degenerate(before2, fromMember))
      {
        return false; // the new triangle would be degenerate
      }
      // Degenerate already (coincident input points, as marching cubes makes where the surface
      // passes through a sample): no worse, and a later collapse removes it. Refusing would
      // lock every collapse around it.
      continue;
    }
    // Which way the original surface under the new triangle faces.
    const float* fu = this->Facing.data() + 3 * static_cast<std::size_t>(tri[(c + 1) % 3]);
    const float* fw = this->Facing.data() + 3 * static_cast<std::size_t>(tri[(c + 2) % 3]);
    const double facing[3] = { merged[0] + fu[0] + fw[0], merged[1] + fu[1] + fw[1],
      merged[2] + fu[2] + fw[2] };
    // A ring triangle may turn by at most the bound from its normal before, or else end within
    // the bound of the original surface's facing: on a noisy input (a scan) normals scatter
    // around the surface's, and the collapses that smooth the noise turn triangles far from
    // their own noisy normal but towards the surface. Refusing those stopped a sphere with 1%
    // noise at 3.7% of its triangles with 13x vtkQuadricDecimation's RMS distance.
    if (before2 > 0.0 &&
      !WithinAngle(Dot(before, after), before2 * after2, rules.MinimumNormalCosine))
    {
      const double facing2 = Dot(facing, facing);
      if (!(facing2 > 0.0 &&
            WithinAngle(Dot(facing, after), facing2 * after2, rules.MinimumNormalCosine)))
      {
        return false;
      }
    }
    if (planeNormal != nullptr && rules.RequireStarShaped)
    {
      const double beforeSide = Dot(before, planeNormal);
      const double side = rules.StarShapedBySide && beforeSide < 0.0 ? -1.0 : 1.0;
      const bool stays = rules.LetWrongSideStay && beforeSide <= 0.0;
      if (side * Dot(after, planeNormal) <= 0.0 && !stays)
      {
        return false;
      }
    }
    // Facing away is refused only for a triangle that faced the right way before: on a very
    // noisy input many triangles face away already (a sphere with radial noise of two thirds
    // of an edge), and refusing every collapse that keeps one so left only collapses making
    // huge triangles, which cut whole caps off (Hausdorff 17% against vtkQuadricDecimation's
    // 2.2% on that sphere, stopped at 3.3% of its triangles asked for 1%).
    // (A triangle degenerate before has no side: it may not come to face away.)
    // (Not where sheets meet: there the facings of sheets of every direction add up.)
    if (rules.KeepFacing && !curve && Dot(after, facing) <= 0.0 &&
      (Dot(before, facing) > 0.0 || !(before2 > tiny)))
    {
      return false;
    }
  }
  return true;
}
} // namespace meshlod
