# Install the build tree BUILD_DIR into PREFIX (removed first) and import `meshlod` from it with
# PYTHON, without the build tree on any path.
file(REMOVE_RECURSE "${PREFIX}")
execute_process(
  COMMAND "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${PREFIX}"
  RESULT_VARIABLE result
  OUTPUT_QUIET)
if (NOT result EQUAL 0)
  message(FATAL_ERROR "cmake --install failed (${result})")
endif ()
file(GLOB_RECURSE init_files "${PREFIX}/*__init__.py")
list(FILTER init_files INCLUDE REGEX "/meshlod/__init__\\.py$")
list(LENGTH init_files count)
if (NOT count EQUAL 1)
  message(FATAL_ERROR "expected one installed meshlod/__init__.py, found: ${init_files}")
endif ()
get_filename_component(package_dir "${init_files}" DIRECTORY)
get_filename_component(python_path "${package_dir}" DIRECTORY)
execute_process(
  COMMAND "${CMAKE_COMMAND}" -E env "PYTHONPATH=${python_path}"
          "${PYTHON}" -c "import meshlod; print(meshlod.__file__); print(meshlod.vtkLODGeomorph().GetClassName())"
  WORKING_DIRECTORY "${PREFIX}"
  RESULT_VARIABLE result
  OUTPUT_VARIABLE output
  ERROR_VARIABLE errors)
message(STATUS "${output}${errors}")
if (NOT result EQUAL 0 OR NOT output MATCHES "vtkLODGeomorph")
  message(FATAL_ERROR "importing the installed meshlod failed")
endif ()
if (NOT output MATCHES "^${PREFIX}")
  message(FATAL_ERROR "meshlod was not imported from ${PREFIX}")
endif ()
