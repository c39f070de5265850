# Tests of the `multimaterialvolume` Python package (Rendering/Python), in
# pvpython through scripts/pvpython, and in a plain Python with ParaView's
# `vtkmodules` (what a VTK Python user runs). Included by CMakeLists.txt.

set(mmv_python_tests
  TestPythonPackage
  TestPythonMaterials
  TestPythonNumerics
  TestPythonBadInput
  TestPythonMapper)
set(mmv_python_environment
  "MMV_PYTHON_PACKAGE_DIR=${MMV_PYTHON_PACKAGE_DIR}"
  "MMV_BUILD_DIR=${CMAKE_BINARY_DIR}")

# A plain interpreter can use the package only where it finds ParaView's
# `vtkmodules`; say so at configure time rather than fail on a setup issue.
execute_process(
  COMMAND "${Python3_EXECUTABLE}" -c "import vtkmodules.vtkCommonCore"
  RESULT_VARIABLE mmv_python_has_vtkmodules
  OUTPUT_QUIET ERROR_QUIET)
if (NOT mmv_python_has_vtkmodules EQUAL 0)
  message(STATUS "${Python3_EXECUTABLE} cannot import vtkmodules: "
    "plain-Python tests of the multimaterialvolume package disabled")
endif ()

foreach (mmv_python_test IN LISTS mmv_python_tests)
  string(REPLACE "TestPython" "" mmv_python_test_name "${mmv_python_test}")
  # scripts/pvpython puts the package (and the plugin) on the path itself.
  add_test(NAME PVPython${mmv_python_test_name}
    COMMAND "${PROJECT_SOURCE_DIR}/scripts/pvpython"
      "${CMAKE_CURRENT_SOURCE_DIR}/${mmv_python_test}.py")
  set_tests_properties(PVPython${mmv_python_test_name} PROPERTIES
    TIMEOUT 120
    ENVIRONMENT
      "${mmv_python_environment};PVPYTHON=${PVPYTHON_EXECUTABLE};PYTHONPATH=${CMAKE_CURRENT_SOURCE_DIR}"
    LABELS "python")
  if (mmv_python_has_vtkmodules EQUAL 0)
    add_test(NAME VTKPython${mmv_python_test_name}
      COMMAND "${Python3_EXECUTABLE}" "${CMAKE_CURRENT_SOURCE_DIR}/${mmv_python_test}.py")
    set_tests_properties(VTKPython${mmv_python_test_name} PROPERTIES
      TIMEOUT 120
      ENVIRONMENT
        "${mmv_python_environment};PYTHONPATH=${MMV_PYTHON_PACKAGE_DIR}:${CMAKE_CURRENT_SOURCE_DIR}"
      LABELS "python")
  endif ()
endforeach ()

# The README's one-liner, and the plugin that scripts/pvpython autoloads
# (its Irradiance Volume filter appears in paraview.simple).
add_test(NAME PVPythonScriptLoadsPackageAndPlugin
  COMMAND "${PROJECT_SOURCE_DIR}/scripts/pvpython" -c
    "import multimaterialvolume as m; f = m.vtkMaterialTransferFunction(); from paraview import simple; assert f.GetClassName() == 'vtkMaterialTransferFunction'; assert hasattr(simple, 'IrradianceVolume'), 'plugin not autoloaded'")
set_tests_properties(PVPythonScriptLoadsPackageAndPlugin PROPERTIES
  TIMEOUT 120
  ENVIRONMENT "${mmv_python_environment};PVPYTHON=${PVPYTHON_EXECUTABLE}"
  LABELS "python")

# Representations created, shown, rendered and deleted in a loop: the live
# objects of the project's classes and the registered proxies come back to
# where they were (the package's vtkMultiMaterialLiveObjects counts them).
add_test(NAME PVPythonRepresentationLifetime
  COMMAND "${PROJECT_SOURCE_DIR}/scripts/pvpython"
    "${CMAKE_CURRENT_SOURCE_DIR}/TestRepresentationLifetime.py")
set_tests_properties(PVPythonRepresentationLifetime PROPERTIES
  TIMEOUT 120
  ENVIRONMENT
    "${mmv_python_environment};PVPYTHON=${PVPYTHON_EXECUTABLE};PYTHONPATH=${CMAKE_CURRENT_SOURCE_DIR}"
  LABELS "python")
