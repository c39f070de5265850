// A render window on an EGL pbuffer of the first GPU device, for running the
// benchmarks on a headless GPU machine without an X server (Debian's VTK 9.2
// is built for GLX only). Chosen by mmvtest::NewRenderWindow() when the
// environment sets MMV_BENCHMARK_EGL=1; see mmvGlewEGLShim.c for the one
// adjustment VTK's GLEW start-up needs under EGL.
#ifndef mmvHeadlessEGLRenderWindow_h
#define mmvHeadlessEGLRenderWindow_h

#include "vtkOpenGLRenderWindow.h"

#include <memory>

class mmvHeadlessEGLRenderWindow : public vtkOpenGLRenderWindow
{
public:
  static mmvHeadlessEGLRenderWindow* New();
  vtkTypeMacro(mmvHeadlessEGLRenderWindow, vtkOpenGLRenderWindow);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  void Initialize() override;
  void Finalize() override;
  void MakeCurrent() override;
  void ReleaseCurrent() override;
  bool IsCurrent() override;
  /// glFinish after every frame, so that a timed Render() includes the GPU's work.
  void Frame() override;
  void SetSize(int width, int height) override;
  using vtkOpenGLRenderWindow::SetSize;
  void* GetGenericContext() override;
  void* GetGenericDisplayId() override;
  vtkTypeBool GetEventPending() override { return 0; }
  void SetFullScreen(vtkTypeBool) override {}
  void WindowRemap() override {}
  void SetWindowInfo(const char*) override {}
  void SetNextWindowInfo(const char*) override {}
  void SetParentInfo(const char*) override {}
  void SetPosition(int x, int y) override;
  using vtkOpenGLRenderWindow::SetPosition;

protected:
  mmvHeadlessEGLRenderWindow();
  ~mmvHeadlessEGLRenderWindow() override;
  void CreateAWindow() override;
  void DestroyWindow() override;

private:
  mmvHeadlessEGLRenderWindow(const mmvHeadlessEGLRenderWindow&) = delete;
  void operator=(const mmvHeadlessEGLRenderWindow&) = delete;
  struct Internals;
  std::unique_ptr<Internals> EGL;
};

#endif
