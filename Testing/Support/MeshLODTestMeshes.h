// Meshes for the tests, the demo and the benchmark: marching-cubes (flying edges) isosurfaces of
// analytic fields at a chosen resolution, and tiny hand-made meshes with known topology.
#ifndef MeshLODTestMeshes_h
#define MeshLODTestMeshes_h

#include "vtkSmartPointer.h"

class vtkAlgorithm;

#include <functional>
#include <string>
#include <vector>

class vtkImageData;
class vtkPolyData;

namespace meshlod
{
namespace testing
{
/// Analytic scalar fields on [-1, 1]^3, contoured at 0.
enum class Field
{
  Sphere,    // closed, genus 0
  Torus,     // closed, genus 1
  Metaballs, // closed, genus 0, one component of five fused blobs with varied curvature
  Gyroid,    // open (cut by the volume box), high genus, no flat parts
  Wavelet,   // vtkRTAnalyticSource-like field: open wavy sheets
};

const char* FieldName(Field field);
bool FieldFromName(const std::string& name, Field& field);

/// The sampled field on a resolution^3 grid spanning [-1, 1]^3 (scalars named "Field").
vtkSmartPointer<vtkImageData> SampleField(Field field, int resolution);

/// Flying-edges isosurface of the field at 0, triangles only, no point data unless asked.
vtkSmartPointer<vtkPolyData> MakeIsosurface(
  Field field, int resolution, bool computeNormals = false, bool computeScalars = false);

/// The resolution whose isosurface has about `triangles` triangles (from a coarse probe).
int ResolutionForTriangles(Field field, double triangles);

// Tiny hand-made meshes. Points are listed in the comment of each maker in the .cxx file.

/// A flat nx by ny grid of squares on z = 0, each split into two triangles (open).
vtkSmartPointer<vtkPolyData> MakeGrid(int nx, int ny);
/// The same grid's squares as quads (cell j * nx + i is square (i, j)), for input that the
/// filters triangulate.
vtkSmartPointer<vtkPolyData> MakeQuadGrid(int nx, int ny);
/// Closed regular octahedron (all vertices valence 4).
vtkSmartPointer<vtkPolyData> MakeOctahedron();
/// Closed regular icosahedron subdivided `levels` times and projected on the unit sphere.
vtkSmartPointer<vtkPolyData> MakeIcosphere(int levels);
/// Closed tetrahedron (valence-3 vertices everywhere).
vtkSmartPointer<vtkPolyData> MakeTetrahedron();
/// Three triangles sharing one edge (a non-manifold edge).
vtkSmartPointer<vtkPolyData> MakeNonManifoldEdge();
/// Two triangle fans touching at a single vertex (a non-manifold "bow tie" vertex).
vtkSmartPointer<vtkPolyData> MakeBowTie();
/// A scan-like open surface: an icosphere subdivided `levels` times (20 * 4^levels triangles),
/// its radii scaled by a smooth bump field and squashed to an ellipsoid (1, 0.8, 0.6), less the
/// triangles within given angles of six directions (six holes of different sizes), cleaned.
vtkSmartPointer<vtkPolyData> MakeBumpySphereWithHoles(int levels);
/// A rough height field over [-1, 1]^2 (an n by n grid, open, heights within about +-0.3).
vtkSmartPointer<vtkPolyData> MakeTerrain(int n);
/// A 4x4 grid with the 2x2 middle squares removed (a hole: two boundary loops).
vtkSmartPointer<vtkPolyData> MakeGridWithHole();
/// A wavy disk of n triangles around one centre point (valence n): an open fan, as a
/// triangulated polygon or a cylinder's cap makes it.
vtkSmartPointer<vtkPolyData> MakeFan(int n);
/// A flat disc in z = 0: a fan of n triangles around the origin out to radius 1, inside a ring
/// of 2n triangles out to radius 2 (open there). The fan's centre and rim are interior.
vtkSmartPointer<vtkPolyData> MakeFlatFanInRing(int n);
/// `cones` closed spindles of `sides` sides, all with their apex at the origin, point 0 (a
/// non-manifold vertex with a wing per spindle), pointing every way (a golden-angle spiral of
/// directions): a fan from the apex to a ring of radius 0.1 at 0.8 along the direction, closed
/// by a fan from the ring to the tip at 1.
vtkSmartPointer<vtkPolyData> MakeConesSharingApex(int cones, int sides);
/// Scan-like noise: every point's position vector scaled by 1 + amplitude (u - 1/2), u uniform
/// in [0, 1) from vtkMinimalStandardRandomSequence with `seed`, in point order (for surfaces
/// centred at the origin).
void PerturbRadially(vtkPolyData* mesh, double amplitude, int seed);

/// The isosurface of a noisy volume, like a CT scan's: a sphere of radius 0.7 with smooth
/// bumps (the field 1 - r / 0.7 + 0.15 sin 5x sin 4y sin 3z) sampled on a resolution^3 grid
/// over [-1, 1]^3, each sample plus uniform noise of up to `noise` times the field's change
/// over one grid step (vtkMinimalStandardRandomSequence with `seed`), contoured at 0 by
/// vtkFlyingEdges3D and cleaned (coincident points merged, degenerate triangles dropped). From
/// a noise of about 1 the surface is rough at the scale of its edges, with small handles,
/// tunnels and separate specks, as isosurfaces of real scans are.
vtkSmartPointer<vtkPolyData> MakeNoisyIsosurface(int resolution, double noise, int seed);

/// Every point of `mesh` multiplied by `scale` (in place).
void Scale(vtkPolyData* mesh, double scale);

/// A unit sphere with its equatorial disk inside: three sheets (the two hemispheres and the
/// disk) meet along the equator, each of whose edges has three triangles. Latitude rings of
/// `around` points, `rings` of them between the poles (odd: the middle one is the equator), and
/// the disk in `diskRings` rings of the same points; Euler characteristic 2 + 1 - 0 = 3.
vtkSmartPointer<vtkPolyData> MakeSphereWithEquatorialDisk(int around, int rings, int diskRings);
/// The output of `source` triangulated (vtkTriangleFilter) and cleaned (vtkCleanPolyData:
/// exactly coincident points merged), as a new data set.
vtkSmartPointer<vtkPolyData> TriangulateAndClean(vtkAlgorithm* source);
/// VTK's wavelet test volume (vtkRTAnalyticSource on [-halfExtent, halfExtent]^3, its own
/// units) contoured at 160 by vtkFlyingEdges3D, triangulated and cleaned: pieces cut open by the
/// volume's faces (small loops where a bulge pokes through a face) and full of handles.
vtkSmartPointer<vtkPolyData> MakeWaveletIsosurface(int halfExtent);
/// A closed surface from a flat list of points and triangles.
vtkSmartPointer<vtkPolyData> MakePolyData(
  const std::vector<double>& points, const std::vector<long long>& triangles);
/// Two copies of a triangle mesh touching at one point: the second copy's points moved by
/// `move` (with `mirrored` its triangles reversed, as a mirror image needs to face outwards),
/// and its point `second` replaced by the first copy's point `first` (its own copy of the point
/// stays, used by no triangle).
vtkSmartPointer<vtkPolyData> MakeTwinTouchingAt(vtkPolyData* mesh,
  vtkIdType first,
  vtkIdType second,
  const std::function<void(double[3])>& move,
  bool mirrored);

/// `mesh`'s triangles with their ids scattered, as a mesh written from a hash map has them: the
/// points renumbered by a random permutation drawn from `seed` (newIds[old] = new, returned when
/// `newIds` is given), point data carried along, and the triangles in a random order, each
/// keeping its corners' order (so its orientation) and its cell data. Other cells are left out.
vtkSmartPointer<vtkPolyData> ShuffleIds(
  vtkPolyData* mesh, unsigned int seed, std::vector<vtkIdType>* newIds = nullptr);

} // namespace testing
} // namespace meshlod

#endif
