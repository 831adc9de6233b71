// The core pieces of vtkLODGeomorph on tiny hand-made meshes with known answers: the collapse
// schedule of the exact-count mode and the edge merge of the nearest-vertex mode.
#include "Core/CollapseSchedule.h"
#include "Core/EdgeMerge.h"
#include "MeshLODTestCheck.h"
#include "MeshLODTestHierarchies.h"
#include "MeshLODTestMeshes.h"

#include "vtkPolyData.h"

#include <initializer_list>
#include <vector>

namespace
{
using namespace meshlod;

// The 3x3 grid (points j * 4 + i; square (i, j) split along a - c into (a, a+1, a+5) and
// (a, a+5, a+4), triangle ids 2 s and 2 s + 1 for square s = 3 j + i), with the four middle
// points 5, 6, 9, 10 clustered into one collapse (rank 0, target 5) and every other point
// fixed.
//
//   12 13 14 15
//    8 [9 10] 11
//    4 [5  6]  7
//    0  1  2  3
// The transition inputs of CollapseSchedule::Build on the 3x3 grid below: every point fixed
// at its own target until Collapse() moves some.
struct GridCollapses
{
  const TriangleMesh Grid = testing::ToTriangleMesh(testing::MakeGrid(3, 3));
  std::vector<Id> Target;
  std::vector<std::int64_t> Rank;
  std::vector<std::uint8_t> AtTarget;
  GridCollapses() { this->Reset(); }
  void Reset()
  {
    this->Target.resize(16);
    for (Id p = 0; p < 16; ++p)
    {
      this->Target[p] = p;
    }
    this->Rank.assign(16, -1);
    this->AtTarget.assign(16, 1);
  }
  // The points merge into `target` as one collapse of the given rank.
  void Collapse(std::initializer_list<Id> points, Id target, std::int64_t rank)
  {
    for (const Id p : points)
    {
      this->Target[p] = target;
      this->Rank[p] = rank;
      this->AtTarget[p] = 0;
    }
  }
  void Build(CollapseSchedule& s) const
  {
    s.Build(this->Grid.Triangles.data(), 18, 16, this->Target.data(), this->Rank.data(),
      this->AtTarget.data());
  }
};

void TestCluster()
{
  GridCollapses grid;
  grid.Collapse({ 5, 6, 9, 10 }, 5, 0);
  CollapseSchedule s;
  grid.Build(s);
  // 5 first (lowest id), then the lowest id joined to a settled point: 6, 9, then 10.
  MESHLOD_CHECK(s.Order == std::vector<Id>({ 5, 6, 9, 10 }));
  MESHLOD_CHECK_EQ(s.Step[0], 0);
  MESHLOD_CHECK_EQ(s.Step[10], 4);
  // 6 joins 5: (1, 6, 5) and (5, 6, 10) go; 9: (5, 10, 9) and (4, 5, 9); 10: (6, 11, 10) and
  // (9, 10, 14).
  MESHLOD_CHECK(s.CountAfter == std::vector<Id>({ 18, 18, 16, 14, 12 }));
  MESHLOD_CHECK_EQ(s.RemovalStep[3], 2);
  MESHLOD_CHECK_EQ(s.RemovalStep[8], 2);
  MESHLOD_CHECK_EQ(s.RemovalStep[9], 3);
  MESHLOD_CHECK_EQ(s.RemovalStep[6], 3);
  MESHLOD_CHECK_EQ(s.RemovalStep[11], 4);
  MESHLOD_CHECK_EQ(s.RemovalStep[14], 4);
  MESHLOD_CHECK_EQ(s.RemovalStep[0], CollapseSchedule::Never);
  MESHLOD_CHECK_EQ(s.StepsForCount(100), 0);
  MESHLOD_CHECK_EQ(s.StepsForCount(18), 0);
  MESHLOD_CHECK_EQ(s.StepsForCount(17), 2);
  MESHLOD_CHECK_EQ(s.StepsForCount(16), 2);
  MESHLOD_CHECK_EQ(s.StepsForCount(15), 3);
  MESHLOD_CHECK_EQ(s.StepsForCount(12), 4);
  MESHLOD_CHECK_EQ(s.StepsForCount(11), -1);
  MESHLOD_CHECK_EQ(s.NextRemovingStep(0), 2);
  MESHLOD_CHECK_EQ(s.NextRemovingStep(2), 3);
  MESHLOD_CHECK_EQ(s.NextRemovingStep(4), -1);

  // Point 9 already at the collapse point: it settles at step 0, then each time the lowest id
  // joined to a settled point: 5 (joined to 9), 6 (joined to 5), 10.
  grid.AtTarget[9] = 1;
  grid.Build(s);
  MESHLOD_CHECK(s.Order == std::vector<Id>({ 5, 6, 10 }));
  MESHLOD_CHECK_EQ(s.Step[9], 0);
  // 5 joins 9: (5, 10, 9) and (4, 5, 9); 6 joins: (1, 6, 5), (5, 6, 10); 10: (6, 11, 10),
  // (9, 10, 14).
  MESHLOD_CHECK(s.CountAfter == std::vector<Id>({ 18, 16, 14, 12 }));

  // Two collapses: {1, 2} (rank 1) and {13, 14} (rank 0): rank order first.
  grid.Reset();
  grid.Collapse({ 1, 2 }, 1, 1);
  grid.Collapse({ 13, 14 }, 13, 0);
  grid.Build(s);
  MESHLOD_CHECK(s.Order == std::vector<Id>({ 13, 14, 1, 2 }));
  // Edge 13-14 has one triangle (9, 14, 13), edge 1-2 one triangle (1, 2, 6): boundary edges.
  MESHLOD_CHECK(s.CountAfter == std::vector<Id>({ 18, 18, 17, 17, 16 }));

  // One collapse {0, 3, 4}: 4 (joined to 0) settles before 3 (joined to neither), so the
  // boundary triangle (0, 5, 4) goes one step earlier than in plain id order.
  grid.Reset();
  grid.Collapse({ 0, 3, 4 }, 0, 0);
  grid.Build(s);
  MESHLOD_CHECK(s.Order == std::vector<Id>({ 0, 4, 3 }));
  MESHLOD_CHECK(s.CountAfter == std::vector<Id>({ 18, 18, 17, 17 }));
}

// The 1x1 grid: edges (0,1) (0,2) (0,3) (1,3) (2,3); merging along (1,3) and (2,3).
void TestEdgeMerge()
{
  const TriangleMesh square = testing::ToTriangleMesh(testing::MakeGrid(1, 1));
  EdgeList edges;
  edges.Build(square.Triangles.data(), 2, 4);
  MESHLOD_CHECK(edges.Ends == std::vector<Id>({ 0, 1, 0, 2, 0, 3, 1, 3, 2, 3 }));
  const std::uint8_t merge[5] = { 0, 0, 0, 1, 1 };
  std::vector<Id> representative;
  MESHLOD_CHECK_EQ(MergeAlongEdges(edges, merge, 4, representative), 2);
  MESHLOD_CHECK(representative == std::vector<Id>({ 0, 1, 1, 1 }));
  const std::uint8_t none[5] = { 0, 0, 0, 0, 0 };
  MESHLOD_CHECK_EQ(MergeAlongEdges(edges, none, 4, representative), 0);
  MESHLOD_CHECK(representative == std::vector<Id>({ 0, 1, 2, 3 }));
}
// A pinch that the next level has too does not hold the steps up. On the same grid, corners 0
// and 15 settle on one target (rank 0: two fans, not a manifold vertex, whatever is merged
// before), 1 and 2 on another (rank 1: a valid edge collapse on its own). The next level has
// that pinched vertex (vertex clustering makes such levels with PreserveTopology off), so no
// step can repair it: the collapses go in rank order and every step is a stop. (Waiting for a
// repair that never comes made the pinching collapse last and, before that, every step after
// it unstoppable: on MakeNoisyIsosurface(120, 1.0, 5)'s levels at 10% and 1% with
// PreserveTopology off, 7 of 38 counts were missed, now 2, by 7 triangles each.) A
// collapse whose target does have one fan in the next level still waits for the neighbour
// that gives it one (TestCollapseWaitsForNeighbour).
void TestPinchOfTheNextLevel()
{
  GridCollapses grid;
  grid.Collapse({ 0, 15 }, 0, 0);
  grid.Collapse({ 1, 2 }, 1, 1);
  CollapseSchedule s;
  grid.Build(s);
  MESHLOD_CHECK(s.Order == std::vector<Id>({ 0, 15, 1, 2 }));
  MESHLOD_CHECK(s.Stops == std::vector<Id>({ 0, 1, 2, 3, 4 }));
}

// A collapse whose merge is valid only after its neighbour's waits for it. Points 1 and 4
// (rank 0) share the neighbours 0 and 5: merged alone they make triangles (0, 1, 5) and
// (0, 5, 4) one triangle twice. Once 0 and 5 (rank 1) are merged, those triangles are gone and
// 1 and 4 become one boundary vertex with one fan. In rank order every step between the two
// merges was unreachable (on a wavelet isosurface's transition of 26,694 to 6,672 triangles,
// every count from 26,694 down to 11,149).
void TestCollapseWaitsForNeighbour()
{
  GridCollapses grid;
  grid.Collapse({ 1, 4 }, 1, 0);
  grid.Collapse({ 0, 5 }, 0, 1);
  CollapseSchedule s;
  grid.Build(s);
  MESHLOD_CHECK(s.Order == std::vector<Id>({ 0, 5, 1, 4 }));
  MESHLOD_CHECK(s.Stops == std::vector<Id>({ 0, 1, 2, 3, 4 }));
  MESHLOD_CHECK(s.CountAfter == std::vector<Id>({ 18, 18, 16, 16, 16 }));
}
} // namespace

int TestGeomorphCore(int, char*[])
{
  TestCluster();
  TestPinchOfTheNextLevel();
  TestCollapseWaitsForNeighbour();
  TestEdgeMerge();
  return meshlod::testing::Result();
}
