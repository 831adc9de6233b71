// Texture baking for simplified levels (Zhou et al., §4): the colour of each texel of a
// TextureAtlas is the colour of the input surface at the point nearest to the texel's position
// on the simplified triangle. The colour there comes from a point colour array (interpolated in
// the nearest input triangle) or from the input's texture looked up at the interpolated texture
// coordinates (bilinear, repeating), so texture seams of the input are respected.
//
// Edge texels are sampled once per edge of the simplified mesh, at points spaced from the
// edge's lower point id, and written into both triangles of the edge: where the two triangles
// got blocks of one size their edge texels are equal, otherwise the finer side interpolates the
// coarser side's samples. The unused half of a single-triangle block is filled by extending the
// triangle, so that bilinear filtering along its diagonal does not pick up foreign colours.
#ifndef MeshLODTextureBaking_h
#define MeshLODTextureBaking_h

#include "Core/TextureAtlas.h"
#include "Core/TriangleMesh.h"
#include "vtkFiltersMeshLODModule.h"
#include "vtkSmartPointer.h"

#include <functional>
#include <string>
#include <vector>

class vtkDataArray;
class vtkImageData;
class vtkPolyData;

namespace meshlod
{
class VTKFILTERSMESHLOD_EXPORT TextureBaker
{
public:
  TextureBaker();
  ~TextureBaker();
  TextureBaker(const TextureBaker&) = delete;
  TextureBaker& operator=(const TextureBaker&) = delete;

  /// Colours from a point array of `surface` (3 or 4 components; unsigned char 0-255 or
  /// floating point 0-1). Returns false with a message when the array cannot be used.
  bool InitializeFromColors(vtkPolyData* surface, vtkDataArray* colors, std::string& error);

  /// Colours from `texture` (unsigned char scalars, 1-4 components) at the point texture
  /// coordinates `tcoords` of `surface`.
  bool InitializeFromTexture(vtkPolyData* surface,
    vtkDataArray* tcoords,
    vtkImageData* texture,
    std::string& error);

  /// Components of the baked images: 4 when the source has alpha, else 3.
  int GetNumberOfComponents() const { return this->Components; }

  /// Bake the texture of `mesh` laid out by `atlas` (unsigned char scalars named "Texture").
  /// The texels go in chunks; after each, `progress` (when given) gets the fraction done and
  /// returns false to stop, and Bake then returns null. It is called on the calling thread.
  vtkSmartPointer<vtkImageData> Bake(const TriangleMesh& mesh, const TextureAtlas& atlas,
    const std::function<bool(double)>& progress = nullptr) const;

  /// The colour (0-255, 4 components) of the input surface nearest to `point`.
  void ColorAt(const double point[3], float rgba[4]) const;

private:
  bool SetSurface(vtkPolyData* surface, std::string& error);
  struct Internals;
  Internals* Impl;
  int Components = 3;
};

} // namespace meshlod

#endif
