#include "mmvHeadlessEGLRenderWindow.h"

#include "vtkObjectFactory.h"
#include "vtkOpenGLState.h"
#include "vtkRenderer.h"
#include "vtkRendererCollection.h"
#include "vtk_glew.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

vtkStandardNewMacro(mmvHeadlessEGLRenderWindow);

struct mmvHeadlessEGLRenderWindow::Internals
{
  EGLDisplay Display = EGL_NO_DISPLAY;
  EGLConfig Config = nullptr;
  EGLContext Context = EGL_NO_CONTEXT;
  EGLSurface Surface = EGL_NO_SURFACE;
};

mmvHeadlessEGLRenderWindow::mmvHeadlessEGLRenderWindow()
  : EGL(new Internals)
{
  this->SetShowWindow(false);
}

mmvHeadlessEGLRenderWindow::~mmvHeadlessEGLRenderWindow()
{
  this->Finalize();
}

void mmvHeadlessEGLRenderWindow::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Context: " << this->EGL->Context << "\n";
}

namespace
{
/// The first GPU device's display (EGL_EXT_platform_device), the default
/// display where that extension is missing.
EGLDisplay OpenDeviceDisplay()
{
  auto queryDevices =
    reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  auto platformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
    eglGetProcAddress("eglGetPlatformDisplayEXT"));
  EGLDeviceEXT devices[8];
  EGLint count = 0;
  if (queryDevices && platformDisplay && queryDevices(8, devices, &count) && count > 0)
  {
    return platformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[0], nullptr);
  }
  return eglGetDisplay(EGL_DEFAULT_DISPLAY);
}
} // namespace

void mmvHeadlessEGLRenderWindow::CreateAWindow()
{
  Internals& egl = *this->EGL;
  if (egl.Display == EGL_NO_DISPLAY)
  {
    egl.Display = OpenDeviceDisplay();
    EGLint major = 0;
    EGLint minor = 0;
    if (egl.Display == EGL_NO_DISPLAY || !eglInitialize(egl.Display, &major, &minor))
    {
      vtkErrorMacro("no EGL display could be initialised");
      egl.Display = EGL_NO_DISPLAY;
      return;
    }
    const EGLint attributes[] = { EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RED_SIZE, 8,
      EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_ALPHA_SIZE, 8, EGL_DEPTH_SIZE, 24,
      EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE };
    EGLint configs = 0;
    if (!eglChooseConfig(egl.Display, attributes, &egl.Config, 1, &configs) || configs == 0)
    {
      vtkErrorMacro("no EGL configuration with RGBA8 and a depth buffer");
      return;
    }
    eglBindAPI(EGL_OPENGL_API);
    egl.Context = eglCreateContext(egl.Display, egl.Config, EGL_NO_CONTEXT, nullptr);
  }
  if (egl.Surface != EGL_NO_SURFACE)
  {
    eglDestroySurface(egl.Display, egl.Surface);
  }
  const EGLint size[] = { EGL_WIDTH, std::max(1, this->Size[0]), EGL_HEIGHT,
    std::max(1, this->Size[1]), EGL_NONE };
  egl.Surface = eglCreatePbufferSurface(egl.Display, egl.Config, size);
  this->Mapped = 0;
  this->MakeCurrent();
}

void mmvHeadlessEGLRenderWindow::DestroyWindow()
{
  Internals& egl = *this->EGL;
  if (egl.Display == EGL_NO_DISPLAY)
  {
    return;
  }
  this->MakeCurrent();
  this->ReleaseGraphicsResources(this);
  eglMakeCurrent(egl.Display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  if (egl.Context != EGL_NO_CONTEXT)
  {
    eglDestroyContext(egl.Display, egl.Context);
  }
  if (egl.Surface != EGL_NO_SURFACE)
  {
    eglDestroySurface(egl.Display, egl.Surface);
  }
  egl = Internals();
}

void mmvHeadlessEGLRenderWindow::Initialize()
{
  if (this->EGL->Context != EGL_NO_CONTEXT)
  {
    return;
  }
  this->CreateAWindow();
  if (this->EGL->Context == EGL_NO_CONTEXT)
  {
    return;
  }
  // The renderers learn about their window's (new) context.
  vtkRenderer* renderer;
  vtkCollectionSimpleIterator it;
  for (this->Renderers->InitTraversal(it); (renderer = this->Renderers->GetNextRenderer(it));)
  {
    renderer->SetRenderWindow(nullptr);
    renderer->SetRenderWindow(this);
  }
  this->OpenGLInit();
}

void mmvHeadlessEGLRenderWindow::Finalize()
{
  this->DestroyWindow();
}

void mmvHeadlessEGLRenderWindow::MakeCurrent()
{
  const Internals& egl = *this->EGL;
  if (egl.Context != EGL_NO_CONTEXT && eglGetCurrentContext() != egl.Context)
  {
    eglMakeCurrent(egl.Display, egl.Surface, egl.Surface, egl.Context);
  }
}

void mmvHeadlessEGLRenderWindow::ReleaseCurrent()
{
  if (this->EGL->Display != EGL_NO_DISPLAY)
  {
    eglMakeCurrent(this->EGL->Display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }
}

bool mmvHeadlessEGLRenderWindow::IsCurrent()
{
  return this->EGL->Context != EGL_NO_CONTEXT && eglGetCurrentContext() == this->EGL->Context;
}

void mmvHeadlessEGLRenderWindow::Frame()
{
  this->MakeCurrent();
  this->Superclass::Frame();
  glFinish();
}

void mmvHeadlessEGLRenderWindow::SetSize(int width, int height)
{
  const bool changed = this->Size[0] != width || this->Size[1] != height;
  this->Superclass::SetSize(width, height);
  if (changed && this->EGL->Surface != EGL_NO_SURFACE)
  {
    this->CreateAWindow();
  }
}

void mmvHeadlessEGLRenderWindow::SetPosition(int x, int y)
{
  this->Position[0] = x;
  this->Position[1] = y;
}

void* mmvHeadlessEGLRenderWindow::GetGenericContext()
{
  return this->EGL->Context;
}

void* mmvHeadlessEGLRenderWindow::GetGenericDisplayId()
{
  return this->EGL->Display;
}
