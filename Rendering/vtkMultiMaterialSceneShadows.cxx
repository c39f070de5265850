#include "vtkMultiMaterialSceneShadows.h"

#include "vtkDataArray.h"
#include "vtkGlobalPrefilteredVolume.h"
#include "vtkImageData.h"
#include "vtkMatrix4x4.h"
#include "vtkMultiMaterialVolumeMapper.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPropCollection.h"
#include "vtkRenderer.h"
#include "vtkSkyVisibility.h" // CoarsenIrradianceGrid
#include "vtkTextureCopy.h"   // UseLinearClamped
#include "vtkTextureObject.h"
#include "vtkVolume.h"
#include "vtkVolumeCollection.h"
#include "vtkVolumeInputScalars.h" // LightingRange
#include "vtkVolumeProperty.h"
#include "vtk_glew.h"

#include <algorithm>
#include <atomic>
#include <chrono>

namespace
{
/// Whether two world boxes share a volume (touching faces do not).
bool BoxesOverlap(const double* a, const double* b)
{
  if (!a || !b)
  {
    return false;
  }
  for (int axis = 0; axis < 3; ++axis)
  {
    if (!(a[2 * axis] < b[2 * axis + 1] && b[2 * axis] < a[2 * axis + 1]))
    {
      return false;
    }
  }
  return true;
}

glm::dmat4 ToGLM(vtkMatrix4x4* m)
{
  glm::dmat4 g;
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      g[c][r] = m->GetElement(r, c); // GLM is column-major
    }
  }
  return g;
}

}

vtkMultiMaterialSceneShadows::vtkMultiMaterialSceneShadows() = default;
vtkMultiMaterialSceneShadows::~vtkMultiMaterialSceneShadows() = default;

const mmv::CoarseExtinction* vtkMultiMaterialSceneShadows::UpdateOccluder(vtkImageData* image,
  vtkDataArray* scalars, int cellFlag, vtkVolumeProperty* property,
  vtkMaterialTransferFunction* materials, int tableSize, std::string* problem)
{
  if (!image || !scalars || !property || image->GetNumberOfPoints() == 0 ||
    scalars->GetNumberOfTuples() == 0)
  {
    return nullptr; // nothing there casts a shadow
  }
  if (cellFlag != 0 || scalars->GetNumberOfComponents() != 1 ||
    scalars->GetNumberOfTuples() != image->GetNumberOfPoints())
  {
    *problem = "only one-component point scalars cast shadows on other volumes; this volume "
               "casts none";
    return nullptr;
  }
  double range[2];
  mmv::LightingRange(scalars, 0, range);
  const std::vector<float> table = mmv::SampleExtinction(property->GetScalarOpacity(0),
    property->GetScalarOpacityUnitDistance(0), materials, range, tableSize);
  this->Extinction.Update(image, scalars, range, table, mmv::SceneShadowVoxelsPerAxis);
  return &this->Extinction;
}

const mmv::CoarseExtinction* vtkMultiMaterialSceneShadows::UpdateOccluder(
  vtkGlobalPrefilteredVolume* global, vtkVolumeProperty* property,
  vtkMaterialTransferFunction* materials, int tableSize)
{
  if (!global || !global->GetValid() || !property || global->GetValues().empty())
  {
    return nullptr;
  }
  const double* range = global->GetScalarRange();
  const std::vector<float> table = mmv::SampleExtinction(property->GetScalarOpacity(0),
    property->GetScalarOpacityUnitDistance(0), materials, range, tableSize);
  this->Extinction.Update(global->GetGrid(), global->GetValues(), global, global->GetMTime(), range,
    table, mmv::SceneShadowVoxelsPerAxis);
  return &this->Extinction;
}

void vtkMultiMaterialSceneShadows::Clear()
{
  this->Occluders.clear();
  this->Key.clear();
  this->Overlapping = false;
}

void vtkMultiMaterialSceneShadows::Gather(
  vtkRenderer* ren, vtkVolume* self, vtkAbstractVolumeMapper* selfMapper)
{
  this->Clear();
  if (!ren || !self)
  {
    return;
  }
  // A collection of our own: vtkRenderer::GetVolumes() keeps the volumes it
  // lists referenced until its next call, which would keep a removed
  // volume (and its mapper) alive.
  vtkNew<vtkVolumeCollection> volumes;
  vtkPropCollection* props = ren->GetViewProps();
  vtkCollectionSimpleIterator pit;
  props->InitTraversal(pit);
  while (vtkProp* prop = props->GetNextProp(pit))
  {
    prop->GetVolumes(volumes);
  }
  const glm::dmat4 selfToWorld = ToGLM(self->GetMatrix());
  const double* selfBounds = self->GetBounds();
  vtkCollectionSimpleIterator it;
  volumes->InitTraversal(it);
  while (vtkVolume* other = volumes->GetNextVolume(it))
  {
    auto* mapper = vtkMultiMaterialVolumeMapper::SafeDownCast(other->GetMapper());
    if (other == self || !other->GetVisibility() || !mapper || mapper == selfMapper)
    {
      continue;
    }
    const mmv::CoarseExtinction* extinction = mapper->GetSceneOccluder(other);
    if (!extinction || extinction->GetValues().empty())
    {
      continue;
    }
    this->Overlapping = this->Overlapping || BoxesOverlap(selfBounds, other->GetBounds());
    vtkNew<vtkMatrix4x4> worldToOther;
    vtkMatrix4x4::Invert(other->GetMatrix(), worldToOther);
    mmv::Occluder occluder;
    occluder.Grid = &extinction->GetGrid();
    occluder.Extinction = &extinction->GetValues();
    occluder.ReceiverToOccluder = ToGLM(worldToOther) * selfToWorld;
    this->Occluders.push_back(occluder);
    this->Key.push_back(static_cast<double>(extinction->GetVersion()));
    const double* m = &occluder.ReceiverToOccluder[0][0];
    this->Key.insert(this->Key.end(), m, m + 16);
  }
}

bool vtkMultiMaterialSceneShadows::Update(vtkOpenGLRenderWindow* context,
  const mmv::IrradianceGrid& grid, const std::vector<mmv::LightSource>& lights,
  std::string* problem)
{
  if (this->Occluders.empty() || lights.empty())
  {
    this->ReleaseGraphicsResources(context); // alone: nothing to read
    return true;
  }
  if (this->HasTextures && this->Key == this->HeldKey && grid.IsSameGrid(this->HeldGrid) &&
    lights == this->HeldLights)
  {
    return true;
  }
  const auto start = std::chrono::steady_clock::now();
  const mmv::IrradianceGrid coarse = mmv::CoarsenToAtMost(grid, mmv::SceneShadowVoxelsPerAxis);
  std::vector<std::vector<float>> groups;
  mmv::ComputeSceneTransmittance(coarse, lights, this->Occluders, groups);
  if (!this->Upload(context, coarse, groups, problem))
  {
    this->ReleaseGraphicsResources(context);
    return false;
  }
  this->HeldKey = this->Key;
  this->HeldGrid = grid;
  this->HeldLights = lights;
  this->HasTextures = true;
  // One counter for every instance, as the estimator compares versions.
  static std::atomic<unsigned long> versions{ 0 };
  this->Version = ++versions;
  ++this->UpdateCount;
  this->LastSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return true;
}

bool vtkMultiMaterialSceneShadows::Upload(vtkOpenGLRenderWindow* context,
  const mmv::IrradianceGrid& coarse, const std::vector<std::vector<float>>& groups,
  std::string* problem)
{
  const int* m = coarse.Dimensions;
  this->Textures.resize(groups.size());
  for (size_t g = 0; g < groups.size(); ++g)
  {
    vtkSmartPointer<vtkTextureObject>& texture = this->Textures[g];
    if (texture && texture->GetHandle() != 0 && static_cast<int>(texture->GetWidth()) == m[0] &&
      static_cast<int>(texture->GetHeight()) == m[1] &&
      static_cast<int>(texture->GetDepth()) == m[2])
    {
      texture->Bind();
      glTexSubImage3D(
        GL_TEXTURE_3D, 0, 0, 0, 0, m[0], m[1], m[2], GL_RGBA, GL_FLOAT, groups[g].data());
      continue;
    }
    if (texture)
    {
      texture->ReleaseGraphicsResources(context);
    }
    texture = vtkSmartPointer<vtkTextureObject>::New();
    texture->SetContext(context);
    // 16-bit float: a transmittance in [0, 1] needs no more than the
    // irradiance it multiplies (16 bits per light).
    texture->SetInternalFormat(GL_RGBA16F);
    texture->SetFormat(GL_RGBA);
    texture->SetDataType(GL_FLOAT);
    if (!texture->Create3DFromRaw(
          m[0], m[1], m[2], 4, VTK_FLOAT, const_cast<float*>(groups[g].data())))
    {
      *problem = "the texture of the other volumes' shadows could not be created";
      texture = nullptr;
      return false;
    }
    mmv::UseLinearClamped(texture);
  }
  return true;
}

std::vector<vtkTextureObject*> vtkMultiMaterialSceneShadows::GetTextures() const
{
  std::vector<vtkTextureObject*> textures;
  for (const auto& texture : this->Textures)
  {
    textures.push_back(texture);
  }
  return textures;
}

void vtkMultiMaterialSceneShadows::ReleaseGraphicsResources(vtkWindow* window)
{
  for (auto& texture : this->Textures)
  {
    if (texture)
    {
      texture->ReleaseGraphicsResources(window);
    }
  }
  this->Textures.clear();
  this->HasTextures = false;
  this->Version = 0;
}
