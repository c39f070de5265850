# The CPU module must not depend on OpenGL (the folders say what depends on
# what). Run with cmake -P:
#   -DLIBRARY=<libvtkMultiMaterialVolumeFilters.so>   must have no OpenGL
#   -DCONTROL=<libvtkMultiMaterialVolume.so>          must have OpenGL (so the
#                                                     check cannot pass vacuously)
#   -DSOURCES=<Filters/>                              no OpenGL header included
#   -DSEARCH=<dir;...>                                where our own libraries are
# Checks the whole runtime closure (what the loader would map), not only the
# direct DT_NEEDED entries, so an OpenGL library reached through a VTK module
# is caught too.
cmake_minimum_required(VERSION 3.16)

# Libraries of OpenGL itself, GLEW and VTK's OpenGL modules.
set(opengl_regex "(^|/)lib(GL|GLX|GLU|OpenGL|EGL|GLEW|GLdispatch)[.-]|vtkglew|vtkRendering[A-Za-z]*OpenGL2")

function (opengl_dependencies library out)
  file(GET_RUNTIME_DEPENDENCIES
    LIBRARIES "${library}"
    DIRECTORIES ${SEARCH}
    RESOLVED_DEPENDENCIES_VAR resolved
    UNRESOLVED_DEPENDENCIES_VAR unresolved)
  if (unresolved)
    message(FATAL_ERROR "Unresolved dependencies of ${library}: ${unresolved}")
  endif ()
  list(LENGTH resolved count)
  if (count LESS 5)
    message(FATAL_ERROR "Only ${count} dependencies found for ${library}: the check is broken")
  endif ()
  set(found)
  foreach (dependency IN LISTS resolved)
    if (dependency MATCHES "${opengl_regex}")
      list(APPEND found "${dependency}")
    endif ()
  endforeach ()
  message(STATUS "${library}: ${count} runtime dependencies, OpenGL ones: ${found}")
  set("${out}" "${found}" PARENT_SCOPE)
endfunction ()

opengl_dependencies("${CONTROL}" control_opengl)
if (NOT control_opengl)
  message(FATAL_ERROR "The control ${CONTROL} shows no OpenGL dependency: the check is broken")
endif ()

opengl_dependencies("${LIBRARY}" library_opengl)
if (library_opengl)
  message(FATAL_ERROR "${LIBRARY} depends on OpenGL: ${library_opengl}")
endif ()

file(GLOB sources "${SOURCES}/*.h" "${SOURCES}/*.cxx" "${SOURCES}/*.in")
list(LENGTH sources source_count)
if (source_count LESS 10)
  message(FATAL_ERROR "Only ${source_count} sources in ${SOURCES}: the check is broken")
endif ()
foreach (source IN LISTS sources)
  file(STRINGS "${source}" includes REGEX "^#include")
  foreach (line IN LISTS includes)
    if (line MATCHES "vtkOpenGL|vtk_glew|vtkglew|GL/|vtkShaderProgram|vtkTextureObject|vtkMultiMaterialVolumeModule")
      message(FATAL_ERROR "${source} includes an OpenGL-side header: ${line}")
    endif ()
  endforeach ()
endforeach ()
message(STATUS "${source_count} sources of ${SOURCES} include no OpenGL-side header")
