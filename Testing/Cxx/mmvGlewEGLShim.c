/* Preloaded (LD_PRELOAD) into the benchmarks when they render through EGL
 * (mmvHeadlessEGLRenderWindow). Debian's VTK 9.2 starts OpenGL with the
 * system GLEW, a GLX build: its glewInit() first loads every GL entry point
 * and only then asks GLX for a display, which an EGL context has not, so it
 * returns GLEW_ERROR_NO_GLX_DISPLAY and VTK gives up although the GL entry
 * points are all there. This turns that one answer into GLEW_OK. */
#define _GNU_SOURCE
#include <GL/glew.h>
#include <dlfcn.h>

GLenum GLEWAPIENTRY glewInit(void)
{
  GLenum (*real)(void) = (GLenum(*)(void))dlsym(RTLD_NEXT, "glewInit");
  const GLenum result = real ? real() : GLEW_ERROR_NO_GL_VERSION;
  return result == GLEW_ERROR_NO_GLX_DISPLAY ? GLEW_OK : result;
}
