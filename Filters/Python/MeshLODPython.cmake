# Python wrapping: the package `meshlod`, importable by the interpreter VTK's Python modules were
# built for (Debian: /usr/bin/python3 with python3-vtk9).
#
# Build tree:   PYTHONPATH=<build>/<MESHLOD_PYTHON_DESTINATION>
# Install tree: <prefix>/<MESHLOD_PYTHON_DESTINATION>; with the default prefix /usr/local this
#               is /usr/local/lib/python3.X/dist-packages, which Debian's python3 searches.

# VTK's own find_package(Python3) may pick another interpreter than the one VTK was built for
# (e.g. one earlier on PATH); pass -DPython3_EXECUTABLE=/usr/bin/python3 when in doubt.
find_package(Python3 REQUIRED COMPONENTS Interpreter Development.Module)

# Debian's interpreter searches <prefix>/lib/python3.X/dist-packages (lib/, never the multiarch
# lib/x86_64-linux-gnu/ that CMAKE_INSTALL_LIBDIR may be).
set(MESHLOD_PYTHON_DESTINATION
  "lib/python${Python3_VERSION_MAJOR}.${Python3_VERSION_MINOR}/dist-packages"
  CACHE STRING "Where the meshlod package goes, relative to the build tree and the prefix")

vtk_module_wrap_python(
  MODULES             ${meshlod_modules}
  TARGET              MeshLOD::PythonModules
  INSTALL_EXPORT      MeshLODPython
  PYTHON_PACKAGE      meshlod
  MODULE_DESTINATION  "${MESHLOD_PYTHON_DESTINATION}"
  CMAKE_DESTINATION   "${CMAKE_INSTALL_LIBDIR}/cmake/MeshLOD"
  LIBRARY_DESTINATION "${CMAKE_INSTALL_LIBDIR}"
  BUILD_STATIC        OFF
  INSTALL_HEADERS     OFF)

# vtk_module_wrap_python makes the extension module but no package __init__.py.
configure_file(
  "${CMAKE_CURRENT_LIST_DIR}/__init__.py"
  "${CMAKE_BINARY_DIR}/${MESHLOD_PYTHON_DESTINATION}/meshlod/__init__.py"
  COPYONLY)
install(
  FILES       "${CMAKE_CURRENT_LIST_DIR}/__init__.py"
  DESTINATION "${MESHLOD_PYTHON_DESTINATION}/meshlod")
