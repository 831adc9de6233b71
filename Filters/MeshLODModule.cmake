# The MeshLOD::FiltersMeshLOD module itself. Included from the top-level CMakeLists.txt when
# vtk_module_build() (ours, or VTK's own for a remote module) re-enters it.

set(meshlod_classes
  vtkLODGeomorph
  vtkTriangleCollapseDecimation
  vtkVertexClusterOctree)

# Exported helpers that are not VTK classes: not wrapped, but usable from C++ (the tests and the
# benchmark measure with the yardstick).
set(meshlod_nowrap_headers
  Filters/MeshLODSurfaceDistance.h)

# Private headers (not installed): the VTK-free algorithm code under Core/ and the glue between
# it and VTK. The tests in the build tree include them directly.
set(meshlod_private_headers
  Filters/Core/CacheHint.h
  Filters/Core/ClusterTree.h
  Filters/Core/CollapseCosts.h
  Filters/Core/CollapseMesh.h
  Filters/Core/CollapseSchedule.h
  Filters/Core/CollapseScheduleBuilder.h
  Filters/Core/Collapser.h
  Filters/Core/EdgeMerge.h
  Filters/Core/FreshMemory.h
  Filters/Core/GroupByKey.h
  Filters/Core/IndexedHeap.h
  Filters/Core/LevelCentering.h
  Filters/Core/LevelData.h
  Filters/Core/LevelEdgeFlips.h
  Filters/Core/LevelTracker.h
  Filters/Core/LevelZeroCorrespondence.h
  Filters/Core/LevelZeroView.h
  Filters/Core/LinkFan.h
  Filters/Core/LocalSurfaceFit.h
  Filters/Core/MergedLink.h
  Filters/Core/OctreeClustering.h
  Filters/Core/OctreeClusteringInternals.h
  Filters/Core/ParallelCompact.h
  Filters/Core/PieceGenus.h
  Filters/Core/Quadric.h
  Filters/Core/RankSelection.h
  Filters/Core/SpatialOrder.h
  Filters/Core/TextureAtlas.h
  Filters/Core/TriangleCollapse.h
  Filters/Core/TriangleMesh.h
  Filters/Core/TriangulationFlips.h
  Filters/Core/Vector3.h
  Filters/MeshLODBlend.h
  Filters/MeshLODGeomorphInternals.h
  Filters/MeshLODHierarchy.h
  Filters/MeshLODInputArrays.h
  Filters/MeshLODInputMesh.h
  Filters/MeshLODNearestCorrespondence.h
  Filters/MeshLODNewArray.h
  Filters/MeshLODSettings.h
  Filters/MeshLODTextureBaking.h
  Filters/MeshLODTriangleTree.h)

set(meshlod_sources
  Filters/Core/ClusterTree.cxx
  Filters/Core/ClusterTreeBuild.cxx
  Filters/Core/CollapseCosts.cxx
  Filters/Core/CollapseLegality.cxx
  Filters/Core/CollapseMesh.cxx
  Filters/Core/CollapseSchedule.cxx
  Filters/Core/CollapseScheduleFans.cxx
  Filters/Core/Collapser.cxx
  Filters/Core/EdgeMerge.cxx
  Filters/Core/FreshMemory.cxx
  Filters/Core/GreedySchedule.cxx
  Filters/Core/IndependentSetSchedule.cxx
  Filters/Core/LevelCentering.cxx
  Filters/Core/LevelEdgeFlips.cxx
  Filters/Core/LevelTracker.cxx
  Filters/Core/LinkFan.cxx
  Filters/Core/LocalSurfaceFit.cxx
  Filters/Core/OctreeClustering.cxx
  Filters/Core/OctreeCuts.cxx
  Filters/Core/OctreeNodes.cxx
  Filters/Core/OctreeRepairs.cxx
  Filters/Core/OctreeSynthesis.cxx
  Filters/Core/OctreeVanishing.cxx
  Filters/Core/PartitionedGreedy.cxx
  Filters/Core/PieceGenus.cxx
  Filters/Core/Quadric.cxx
  Filters/Core/SpatialOrder.cxx
  Filters/Core/TextureAtlas.cxx
  Filters/Core/TriangleCollapse.cxx
  Filters/Core/TriangleMesh.cxx
  Filters/Core/TriangulationFlips.cxx
  Filters/MeshLODBlend.cxx
  Filters/MeshLODGeomorphFlips.cxx
  Filters/MeshLODGeomorphInternals.cxx
  Filters/MeshLODHierarchy.cxx
  Filters/MeshLODInputArrays.cxx
  Filters/MeshLODInputMesh.cxx
  Filters/MeshLODNearestCorrespondence.cxx
  Filters/MeshLODNewArray.cxx
  Filters/MeshLODSurfaceDistance.cxx
  Filters/MeshLODTextureBaking.cxx
  Filters/MeshLODTriangleTree.cxx)

list(TRANSFORM meshlod_classes PREPEND "Filters/")

vtk_module_add_module(MeshLOD::FiltersMeshLOD
  CLASSES         ${meshlod_classes}
  SOURCES         ${meshlod_sources}
  NOWRAP_HEADERS  ${meshlod_nowrap_headers}
  PRIVATE_HEADERS ${meshlod_private_headers})
vtk_module_include(MeshLOD::FiltersMeshLOD
  PUBLIC
    "$<BUILD_INTERFACE:${CMAKE_CURRENT_LIST_DIR}>")

# The blend renormalises normals every frame: without errno, sqrt is a single instruction with
# no library call behind it (nothing in MeshLOD reads errno), and without trapping math the
# renormalisation loop is vectorised (nothing in MeshLOD traps floating-point exceptions).
set_source_files_properties(Filters/MeshLODBlend.cxx
  PROPERTIES
    COMPILE_OPTIONS
      "$<$<CXX_COMPILER_ID:GNU,Clang,AppleClang>:-fno-math-errno;-fno-trapping-math>")
