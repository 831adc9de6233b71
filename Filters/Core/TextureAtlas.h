// MeshLOD core: texture atlas layout for a simplified mesh (Zhou et al., §4).
//
// Every triangle gets a half-square (right isosceles) triangle in a square power-of-two texture,
// with its corners on texel centres. Adjacent triangles are paired across an edge into one
// square block that they split along its diagonal, so the texels of that shared edge are the
// same for both. A block's size is a power of two chosen from the area of its triangles, with
// one texel density for the whole mesh, the largest whose blocks still fit; blocks are packed in
// Morton order (largest first), which leaves no gaps between power-of-two squares.
//
// Block layout (S = Size - 1 texel steps; the diagonal runs from (S, 0) to (0, S)):
//
//     (0,S) b_________ apex of the upper triangle (S,S)
//           |\        |
//           |  \ upper|
//           |lower\   |
//           |       \ |
//     (0,0) apex_____\ a (S,0)
//
// The lower triangle's apex is the corner opposite its longest (or paired) edge a -> b. The
// mesh's points are split per block: a texture coordinate is attached to each copy.
#ifndef meshlod_TextureAtlas_h
#define meshlod_TextureAtlas_h

#include "TriangleMesh.h"
#include "vtkFiltersMeshLODModule.h"

#include <vector>

namespace meshlod
{
struct VTKFILTERSMESHLOD_EXPORT TextureAtlas
{
  struct Block
  {
    Id X = 0;    // lowest texel column
    Id Y = 0;    // lowest texel row
    Id Size = 0; // texels per side, a power of two (at least 2)
    Id Lower = InvalidId;
    Id Upper = InvalidId; // InvalidId: the upper half is padding
  };

  Id Resolution = 0; // texture edge in texels (a power of two)
  // The resolution asked for, rounded up to a power of two: Resolution is larger when the
  // level has too many triangles for it.
  Id RequestedResolution = 0;
  std::vector<Block> Blocks;
  std::vector<Id> TriangleBlock; // triangle -> block
  std::vector<Id> CornerTexel;   // 2 per triangle corner: texel column and row
  std::vector<Id> CornerPoint;   // 3 per triangle: split point of each corner
  std::vector<Id> SplitPoints;   // split point -> point of the mesh

  /// Texture coordinate of texel (x, y)'s centre.
  double U(Id x) const { return (x + 0.5) / static_cast<double>(this->Resolution); }
};

/// Lay out the atlas of `mesh` in a texture of `resolution` texels per side (rounded up to a
/// power of two, and raised further when even the smallest blocks would not fit: check
/// atlas.Resolution).
VTKFILTERSMESHLOD_EXPORT void BuildTextureAtlas(const TriangleMesh& mesh,
  Id resolution,
  TextureAtlas& atlas);

} // namespace meshlod

#endif
