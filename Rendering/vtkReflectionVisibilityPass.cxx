#include "vtkReflectionVisibilityPass.h"

#include "vtkIrradianceRegion.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkOpenGLVertexArrayObject.h"
#include "vtkShaderProgram.h"
#include "vtkSmartPointer.h"
#include "vtkTextureCopy.h" // UseLinearClamped
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include "mmvCutaway.h"
#include "mmvLayerGS.h"
#include "mmvLayerVS.h"
#include "mmvReflectionMarch.h"
#include "mmvReflectionVisibilityFS.h"
#include "mmvShadowRay.h"
#include "mmvVoxelPassDec.h"
#include "mmvVoxelPassMain.h"

#include <algorithm>
#include <memory>

vtkStandardNewMacro(vtkReflectionVisibilityPass);

class vtkReflectionVisibilityPass::vtkInternals
{
public:
  vtkSmartPointer<vtkTextureObject> Texture;
  vtkSmartPointer<vtkOpenGLFramebufferObject> Framebuffer;
  std::unique_ptr<vtkOpenGLQuadHelper> Quad;
  std::string Source;
  std::vector<double> Key; // empty: nothing computed

  bool Allocate(vtkOpenGLRenderWindow* context, const int d[3]);
  vtkShaderProgram* Ready(vtkOpenGLRenderWindow* context, const std::string& defines);
};

bool vtkReflectionVisibilityPass::vtkInternals::Allocate(
  vtkOpenGLRenderWindow* context, const int d[3])
{
  vtkTextureObject* t = this->Texture;
  if (t && t->GetHandle() && static_cast<int>(t->GetWidth()) == d[0] &&
    static_cast<int>(t->GetHeight()) == d[1] && static_cast<int>(t->GetDepth()) == d[2])
  {
    return true;
  }
  // 16-bit unsigned normalised, as the irradiance: I is a fraction in [0, 1].
  this->Texture = vtkSmartPointer<vtkTextureObject>::New();
  this->Texture->SetContext(context);
  this->Texture->SetInternalFormat(GL_R16);
  this->Texture->SetFormat(GL_RED);
  this->Texture->SetDataType(GL_UNSIGNED_SHORT);
  mmv::UseLinearClamped(this->Texture);
  std::vector<unsigned short> zeros(static_cast<size_t>(d[0]) * d[1] * d[2], 0);
  return this->Texture->Create3DFromRaw(d[0], d[1], d[2], 1, VTK_UNSIGNED_SHORT, zeros.data());
}

vtkShaderProgram* vtkReflectionVisibilityPass::vtkInternals::Ready(
  vtkOpenGLRenderWindow* context, const std::string& defines)
{
  std::string source = "//VTK::System::Dec\n" + defines + mmvCutaway + "\n//VTK::Output::Dec\n";
  source += mmvVoxelPassDec;
  source += mmvShadowRay;
  source += mmvReflectionMarch;
  source += mmvReflectionVisibilityFS;
  source += mmvVoxelPassMain;
  if (!this->Quad || this->Source != source)
  {
    if (this->Quad)
    {
      this->Quad->ReleaseGraphicsResources(context);
    }
    this->Source = source;
    this->Quad =
      std::make_unique<vtkOpenGLQuadHelper>(context, mmvLayerVS, source.c_str(), mmvLayerGS);
  }
  if (!this->Quad->Program || !context->GetShaderCache()->ReadyShaderProgram(this->Quad->Program))
  {
    return nullptr;
  }
  return this->Quad->Program;
}

vtkReflectionVisibilityPass::vtkReflectionVisibilityPass()
  : Internals(new vtkInternals)
{
}

vtkReflectionVisibilityPass::~vtkReflectionVisibilityPass()
{
  delete this->Internals;
}

vtkTextureObject* vtkReflectionVisibilityPass::GetVisibilityTexture() const
{
  return this->Internals->Key.empty() ? nullptr : this->Internals->Texture.Get();
}

bool vtkReflectionVisibilityPass::Update(vtkOpenGLRenderWindow* context, const int dims[3],
  const int* region, const std::string& defines, const std::vector<double>& key,
  const std::function<void(vtkShaderProgram*)>& setUniforms)
{
  vtkInternals& in = *this->Internals;
  if (!key.empty() && key == in.Key && in.Texture)
  {
    return true;
  }
  in.Key.clear();
  vtkShaderProgram* program = in.Allocate(context, dims) ? in.Ready(context, defines) : nullptr;
  if (!program)
  {
    vtkErrorMacro("cannot compute the reflections' visibility: the context lacks 3D render "
                  "targets or the shader did not build");
    return false;
  }
  if (!in.Framebuffer)
  {
    in.Framebuffer = vtkSmartPointer<vtkOpenGLFramebufferObject>::New();
    in.Framebuffer->SetContext(context);
  }
  vtkOpenGLState* state = context->GetState();
  state->PushFramebufferBindings();
  {
    vtkOpenGLState::ScopedglViewport viewport(state);
    vtkOpenGLState::ScopedglEnableDisable blend(state, GL_BLEND);
    vtkOpenGLState::ScopedglEnableDisable depth(state, GL_DEPTH_TEST);
    vtkOpenGLState::ScopedglEnableDisable scissor(state, GL_SCISSOR_TEST);
    vtkOpenGLState::ScopedglColorMask colorMask(state);
    vtkOpenGLState::ScopedglScissor scissorBox(state); // the region's, restored for the ray cast
    state->vtkglDisable(GL_BLEND);
    state->vtkglDisable(GL_DEPTH_TEST);
    state->vtkglDisable(GL_SCISSOR_TEST);
    state->vtkglColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    state->vtkglViewport(0, 0, dims[0], dims[1]);
    mmv::IndexBox box = mmv::IndexBox::Whole(dims);
    if (region)
    {
      mmv::IndexBox requested;
      std::copy(region, region + 6, requested.Bounds);
      box = box.Intersected(requested);
    }
    const int* b = box.Bounds;
    if (region && !box.IsEmpty())
    {
      state->vtkglEnable(GL_SCISSOR_TEST);
      state->vtkglScissor(b[0], b[2], b[1] - b[0] + 1, b[3] - b[2] + 1);
    }
    setUniforms(program);
    // The region's slices (every slice without one) in one instanced draw
    // into the whole 3D texture.
    in.Framebuffer->Bind();
    glFramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, in.Texture->GetHandle(), 0);
    in.Framebuffer->ActivateDrawBuffers(1);
    program->SetUniformi("firstLayer", b[4]);
    in.Quad->VAO->Bind();
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, box.IsEmpty() ? 0 : b[5] - b[4] + 1);
    in.Quad->VAO->Release();
    glFramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, 0, 0);
  }
  state->PopFramebufferBindings();
  in.Key = key;
  ++this->UpdateCount;
  return true;
}

void vtkReflectionVisibilityPass::ReleaseGraphicsResources(vtkWindow* window)
{
  vtkInternals& in = *this->Internals;
  if (in.Quad)
  {
    in.Quad->ReleaseGraphicsResources(window);
    in.Quad.reset();
  }
  if (in.Texture)
  {
    in.Texture->ReleaseGraphicsResources(window);
    in.Texture = nullptr;
  }
  if (in.Framebuffer)
  {
    in.Framebuffer->ReleaseGraphicsResources(window);
    in.Framebuffer = nullptr;
  }
  in.Source.clear();
  in.Key.clear();
}

void vtkReflectionVisibilityPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "UpdateCount: " << this->UpdateCount << "\n";
}
