#include "vtkMultiMaterialSky.h"

#include "vtkCoarseExtinction.h"
#include "vtkIrradianceDiffusion.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialEnvironment.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkMultiMaterialVolumeGeometry.h" // SamePointsMap
#include "vtkSkyVisibility.h"
#include "vtkTextureCopy.h" // UseLinearClamped

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkMatrix4x4.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPiecewiseFunction.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtkVolumeProperty.h"
#include "vtk_glew.h"

#include <algorithm>
#include <chrono>
#include <cmath>

bool vtkMultiMaterialSky::Key::operator==(const Key& o) const
{
  return this->Points.IsSameGrid(o.Points) && this->Scalars == o.Scalars &&
    this->ScalarsTime == o.ScalarsTime && this->Range[0] == o.Range[0] &&
    this->Range[1] == o.Range[1] && this->Extinction == o.Extinction &&
    this->Scattering == o.Scattering && this->Exponential == o.Exponential;
}

vtkMultiMaterialSky::vtkMultiMaterialSky() = default;
vtkMultiMaterialSky::~vtkMultiMaterialSky() = default;

bool vtkMultiMaterialSky::Refresh(
  const mmv::SkyInputs& in, std::vector<std::string>& warnings, std::string& error)
{
  std::string why;
  const double strength = mmv::ValidEnvironmentLighting(in.Strength, &why);
  if (!why.empty())
  {
    warnings.push_back(why);
  }
  if (strength == 0.0)
  {
    return false;
  }
  if (in.Distributed)
  {
    warnings.emplace_back("the environment light is not estimated across the pieces of a "
                          "distributed volume; the sky is off");
    return false;
  }
  if (this->SetColors(in.Renderer, in.WorldToObject, strength, in.UseTexture, &warnings))
  {
    return false; // a black sky lights nothing: no sky code
  }
  return this->Update(
    vtkOpenGLRenderWindow::SafeDownCast(in.Renderer->GetRenderWindow()), in, &error);
}

bool vtkMultiMaterialSky::Update(
  vtkOpenGLRenderWindow* context, const mmv::SkyInputs& in, std::string* problem)
{
  int dims[3];
  in.Image->GetDimensions(dims);
  const mmv::IrradianceGrid points = mmv::MakeIrradianceGrid(in.Image, dims);
  const mmv::IrradianceGrid grid = mmv::CoarsenToAtMost(points, mmv::SkyVoxelsPerAxis);
  Key key;
  key.Scalars = in.Scalars;
  key.ScalarsTime = in.Scalars->GetMTime();
  key.Points = points;
  key.Range[0] = in.Range[0];
  key.Range[1] = in.Range[1];
  key.Exponential = in.ExponentialDiffusion;
  // The extinction the shadows see: the attenuation times the opacity's.
  key.Extinction = mmv::SampleExtinction(in.Property->GetScalarOpacity(0),
    in.Property->GetScalarOpacityUnitDistance(0), in.Materials, in.Range, in.TableSize);
  bool scatters = false;
  std::vector<float> scattering(key.Extinction.size(), 0.0f);
  for (int i = 0; in.MultipleScattering && in.Materials && i < in.TableSize; ++i)
  {
    const double s = in.Range[0] + (in.Range[1] - in.Range[0]) * i / (in.TableSize - 1.0);
    if (key.Extinction[i] > 0.0f)
    {
      scattering[i] = static_cast<float>(in.Materials->EvaluateParameter(s, mmv::Scattering));
      scatters = scatters || scattering[i] > 0.0f;
    }
  }
  if (scatters)
  {
    key.Scattering = scattering;
  }
  if (this->HasKey && key == this->Held && this->Texture && this->Texture->GetHandle() != 0)
  {
    return true;
  }
  const auto start = std::chrono::steady_clock::now();
  const bool kept = this->RestoreKept(key, grid);
  if (!kept)
  {
    this->EstimateMoments(in.Image, in.Scalars, key);
    if (!key.Scattering.empty())
    {
      this->DiffuseMoments(points, grid, key);
    }
    this->Kept.push_front(KeptMoments{ key, grid, this->Moments });
    if (this->Kept.size() > MaxKept)
    {
      this->Kept.pop_back();
    }
  }
  if (!this->Upload(context, grid, problem))
  {
    return false;
  }
  this->Grid = grid;
  std::copy(dims, dims + 3, this->DataDimensions);
  this->Held = key;
  this->HasKey = true;
  if (!kept)
  {
    ++this->UpdateCount;
    this->LastSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  return true;
}

bool vtkMultiMaterialSky::RestoreKept(const Key& key, const mmv::IrradianceGrid& grid)
{
  for (auto entry = this->Kept.begin(); entry != this->Kept.end(); ++entry)
  {
    if (entry->From == key &&
      std::equal(grid.Dimensions, grid.Dimensions + 3, entry->Grid.Dimensions))
    {
      this->Moments = entry->Moments;
      this->Kept.splice(this->Kept.begin(), this->Kept, entry);
      return true;
    }
  }
  return false;
}

void vtkMultiMaterialSky::EstimateMoments(
  vtkImageData* image, vtkDataArray* scalars, const Key& key)
{
  this->Extinction.Update(image, scalars, key.Range, key.Extinction, mmv::SkyVoxelsPerAxis);
  mmv::ComputeSkyVisibility(this->Extinction.GetGrid(), this->Extinction.GetValues().data(),
    mmv::SkyDirections(mmv::SkyDirectionCount), this->Moments);
}

void vtkMultiMaterialSky::DiffuseMoments(
  const mmv::IrradianceGrid& points, const mmv::IrradianceGrid& grid, const Key& key)
{
  std::vector<float> strength;
  mmv::AverageOntoGrid(
    points, this->Extinction.GetNormalized().data(), grid, strength, &key.Scattering);
  // s is in data voxels^2: the sky's grid spacing in data voxels.
  const double spacing[3] = { grid.DataVoxelsPerVoxel.x, grid.DataVoxelsPerVoxel.y,
    grid.DataVoxelsPerVoxel.z };
  mmv::DiffusionSettings settings;
  settings.Exponential = key.Exponential;
  mmv::DiffuseSkyMoments(grid.Dimensions, spacing, strength.data(), this->Moments, settings);
}

bool vtkMultiMaterialSky::Upload(
  vtkOpenGLRenderWindow* context, const mmv::IrradianceGrid& grid, std::string* problem)
{
  if (!this->Texture)
  {
    this->Texture = vtkSmartPointer<vtkTextureObject>::New();
  }
  vtkTextureObject* texture = this->Texture;
  texture->SetContext(context);
  const int* m = grid.Dimensions;
  if (texture->GetHandle() != 0 && static_cast<int>(texture->GetWidth()) == m[0] &&
    static_cast<int>(texture->GetHeight()) == m[1] && static_cast<int>(texture->GetDepth()) == m[2])
  {
    texture->Bind();
    glTexSubImage3D(
      GL_TEXTURE_3D, 0, 0, 0, 0, m[0], m[1], m[2], GL_RGBA, GL_FLOAT, this->Moments.data());
  }
  else
  {
    texture->ReleaseGraphicsResources(context);
    texture->SetContext(context);
    texture->SetInternalFormat(GL_RGBA32F);
    texture->SetFormat(GL_RGBA);
    texture->SetDataType(GL_FLOAT);
    if (!texture->Create3DFromRaw(m[0], m[1], m[2], 4, VTK_FLOAT, this->Moments.data()))
    {
      *problem = "the sky's visibility texture could not be created";
      return false;
    }
  }
  mmv::UseLinearClamped(texture);
  return true;
}

bool vtkMultiMaterialSky::SetColors(vtkRenderer* ren, vtkMatrix4x4* worldToObject, double strength,
  bool useTexture, std::vector<std::string>* problems)
{
  vtkNew<vtkMatrix4x4> objectToWorld;
  vtkMatrix4x4::Invert(worldToObject, objectToWorld);
  vtkMultiMaterialEnvironment* environment = this->Environment;
  environment->Update(ren, objectToWorld,
    useTexture ? mmv::ReflectEnvironmentTexture : mmv::ReflectBackground, problems);
  glm::dvec3 mean;
  glm::dmat3 slope;
  environment->FitLinear(mean, slope);
  this->Mean = glm::vec3(strength * mean);
  this->Slope = glm::mat3(strength * slope);
  return glm::length(this->Mean) <= 0.0f;
}

void vtkMultiMaterialSky::SetUniforms(vtkShaderProgram* program) const
{
  program->SetUniformi("mmv_sky", this->Texture->GetTextureUnit());
  float scale[3], bias[3];
  for (int a = 0; a < 3; ++a)
  {
    mmv::SamePointsMap(this->DataDimensions[a], this->Grid.Dimensions[a], scale[a], bias[a]);
  }
  program->SetUniform3f("mmv_skyScale", scale);
  program->SetUniform3f("mmv_skyBias", bias);
  program->SetUniform3f("mmv_skyMean", &this->Mean[0]);
  program->SetUniformMatrix3x3("mmv_skySlope", const_cast<float*>(&this->Slope[0][0]));
}

void vtkMultiMaterialSky::Activate()
{
  if (this->Texture)
  {
    this->Texture->Activate();
  }
}

void vtkMultiMaterialSky::Deactivate()
{
  if (this->Texture)
  {
    this->Texture->Deactivate();
  }
}

void vtkMultiMaterialSky::ReleaseGraphicsResources(vtkWindow* window)
{
  if (this->Texture)
  {
    this->Texture->ReleaseGraphicsResources(window);
  }
  this->HasKey = false; // the kept moments are on the CPU: they stay
}
