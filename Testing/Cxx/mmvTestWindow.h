// The render windows of the tests and benchmarks: VTK's own (GLX under X) by
// default, or an EGL pbuffer on the GPU when MMV_BENCHMARK_EGL=1, for
// headless GPU machines (run with LD_PRELOAD of libmmvGlewEGLShim.so; see
// mmvGlewEGLShim.c).
#ifndef mmvTestWindow_h
#define mmvTestWindow_h

#include "mmvHeadlessEGLRenderWindow.h"

#include "vtkRenderWindow.h"
#include "vtkSmartPointer.h"

#include <cstdlib>
#include <string>

namespace mmvtest
{
inline vtkSmartPointer<vtkRenderWindow> NewRenderWindow()
{
  const char* egl = std::getenv("MMV_BENCHMARK_EGL");
  if (egl && std::string(egl) == "1")
  {
    return vtkSmartPointer<mmvHeadlessEGLRenderWindow>::New();
  }
  return vtkSmartPointer<vtkRenderWindow>::New();
}

/// The OpenGL renderer string of the window's context, to label figures.
inline std::string RendererString(vtkRenderWindow* window)
{
  const std::string caps = window->ReportCapabilities();
  const std::string key = "OpenGL renderer string:";
  const size_t at = caps.find(key);
  if (at == std::string::npos)
  {
    return "unknown";
  }
  std::string s = caps.substr(at + key.size(), caps.find('\n', at) - at - key.size());
  s.erase(0, s.find_first_not_of(' '));
  return s;
}
} // namespace mmvtest

#endif
