#include "vtkMultiMaterialEnvironment.h"

#include "vtkAlgorithm.h"
#include "vtkAlgorithmOutput.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkMatrix4x4.h"
#include "vtkMultiMaterialShading.h"
#include "vtkMultiMaterialVolumeSampling.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkRenderer.h"
#include "vtkSkyVisibility.h"
#include "vtkTexture.h"

#include <algorithm>
#include <cmath>

vtkStandardNewMacro(vtkMultiMaterialEnvironment);

vtkMultiMaterialEnvironment::vtkMultiMaterialEnvironment() = default;
vtkMultiMaterialEnvironment::~vtkMultiMaterialEnvironment() = default;

namespace
{
glm::dvec3 PullBack(vtkMatrix4x4* objectToWorld, const double* w)
{
  // Object-space covector of world axis w: dot(L d, w) = dot(d, L^T w).
  glm::dvec3 a(0.0);
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      a[i] += objectToWorld->GetElement(j, i) * w[j];
    }
  }
  return a;
}

glm::dvec3 Cross(const double* a, const double* b)
{
  return glm::cross(glm::dvec3(a[0], a[1], a[2]), glm::dvec3(b[0], b[1], b[2]));
}
}

//------------------------------------------------------------------------------
bool vtkMultiMaterialEnvironment::SetBackgroundOverride(const double bottom[3], const double top[3])
{
  const glm::dvec3 b(bottom[0], bottom[1], bottom[2]);
  const glm::dvec3 t(top[0], top[1], top[2]);
  if (this->Override && b == this->OverrideBottom && t == this->OverrideTop)
  {
    return false;
  }
  this->Override = true;
  this->OverrideBottom = b;
  this->OverrideTop = t;
  return true;
}

bool vtkMultiMaterialEnvironment::ClearBackgroundOverride()
{
  const bool changed = this->Override;
  this->Override = false;
  return changed;
}

//------------------------------------------------------------------------------
void vtkMultiMaterialEnvironment::Update(
  vtkRenderer* ren, vtkMatrix4x4* objectToWorld, int source, std::vector<std::string>* problems)
{
  vtkNew<vtkMatrix4x4> worldToObject;
  vtkMatrix4x4::Invert(objectToWorld, worldToObject);
  this->ViewUp = mmv::ViewUpInObject(ren->GetActiveCamera(), worldToObject);
  const double* bottom = ren->GetBackground();
  const double* top = ren->GetGradientBackground() ? ren->GetBackground2() : bottom;
  this->Bottom =
    this->Override ? this->OverrideBottom : glm::dvec3(bottom[0], bottom[1], bottom[2]);
  this->Top = this->Override ? this->OverrideTop : glm::dvec3(top[0], top[1], top[2]);

  this->Kind = mmv::BackgroundEnvironment;
  this->Texture = nullptr;
  this->Images.clear();
  vtkTexture* texture = ren->GetEnvironmentTexture();
  if (source != mmv::ReflectEnvironmentTexture || !texture)
  {
    return;
  }
  std::string problem;
  if (!this->ReadTexture(texture, problem))
  {
    this->Images.clear();
    if (problems)
    {
      problems->push_back("the renderer's environment texture " + problem +
        ": reflecting the background colours instead");
    }
    return;
  }
  this->Texture = texture;
  this->Kind = texture->GetCubeMap() ? mmv::CubeMapEnvironment : mmv::EquirectangularEnvironment;
  this->Interpolate = texture->GetInterpolate() != 0;
  this->Repeat = texture->GetRepeat() != 0 && !texture->GetEdgeClamp();
  this->SRGB = texture->GetUseSRGBColorSpace();
  const double* up = ren->GetEnvironmentUp();
  const double* right = ren->GetEnvironmentRight();
  const glm::dvec3 front = Cross(up, right);
  const double frontArray[3] = { front.x, front.y, front.z };
  this->Right = PullBack(objectToWorld, right);
  this->Up = PullBack(objectToWorld, up);
  this->Front = PullBack(objectToWorld, frontArray);
}

//------------------------------------------------------------------------------
bool vtkMultiMaterialEnvironment::ReadTexture(vtkTexture* texture, std::string& problem)
{
  // A cube map's faces are input ports 0-5, a 2D texture's image port 0.
  const int expected = texture->GetCubeMap() ? 6 : 1;
  int connected = 0;
  for (int port = 0; port < std::min(expected, texture->GetNumberOfInputPorts()); ++port)
  {
    connected += texture->GetNumberOfInputConnections(port) > 0 ? 1 : 0;
  }
  if (connected < expected)
  {
    problem = texture->GetCubeMap()
      ? "is a cube map with " + std::to_string(connected) + " of its 6 faces"
      : "has no image";
    return false;
  }
  int faceDims[3] = { 0, 0, 0 };
  for (int i = 0; i < expected; ++i)
  {
    vtkAlgorithmOutput* port = texture->GetInputConnection(i, 0);
    if (port && port->GetProducer())
    {
      port->GetProducer()->Update(port->GetIndex());
    }
    vtkImageData* image = vtkImageData::SafeDownCast(texture->GetInputDataObject(i, 0));
    if (!image)
    {
      problem = "has an input that is not an image";
      return false;
    }
    int dims[3];
    image->GetDimensions(dims);
    vtkDataArray* scalars = image->GetPointData()->GetScalars();
    if (image->GetNumberOfPoints() == 0 || !scalars || scalars->GetNumberOfTuples() == 0 ||
      scalars->GetNumberOfComponents() < 1 || scalars->GetNumberOfComponents() > 4)
    {
      problem = "is empty (an image without points or colour scalars)";
      return false;
    }
    if (dims[2] != 1)
    {
      problem = "is not a 2D image or cube map (an image of " + std::to_string(dims[0]) + " x " +
        std::to_string(dims[1]) + " x " + std::to_string(dims[2]) + " points)";
      return false;
    }
    if (i > 0 && (dims[0] != faceDims[0] || dims[1] != faceDims[1]))
    {
      problem = "is a cube map whose faces differ in size";
      return false;
    }
    std::copy(dims, dims + 3, faceDims);
    this->Images.emplace_back(image);
  }
  return true;
}

//------------------------------------------------------------------------------
glm::dvec3 vtkMultiMaterialEnvironment::Texel(int image, int i, int j) const
{
  vtkImageData* data = this->Images[image];
  const int* dims = data->GetDimensions();
  vtkDataArray* scalars = data->GetPointData()->GetScalars();
  const vtkIdType id = static_cast<vtkIdType>(j) * dims[0] + i;
  const int components = scalars->GetNumberOfComponents();
  const double scale = scalars->GetDataType() == VTK_UNSIGNED_CHAR ? 1.0 / 255.0 : 1.0;
  glm::dvec3 c;
  for (int k = 0; k < 3; ++k)
  {
    // One or two components (grey, grey + alpha): grey in every channel.
    const double value = scalars->GetComponent(id, components < 3 ? 0 : k) * scale;
    c[k] = this->SRGB ? mmv::SRGBToLinear(value) : value;
  }
  return c;
}

glm::dvec3 vtkMultiMaterialEnvironment::SampleImage(
  int image, const glm::dvec2& st, bool repeat) const
{
  const int* dims = this->Images[image]->GetDimensions();
  auto wrap = [repeat](int i, int n)
  {
    if (repeat)
    {
      return ((i % n) + n) % n;
    }
    return std::min(std::max(i, 0), n - 1);
  };
  const double x = st.x * dims[0];
  const double y = st.y * dims[1];
  if (!this->Interpolate)
  {
    return this->Texel(image, wrap(static_cast<int>(std::floor(x)), dims[0]),
      wrap(static_cast<int>(std::floor(y)), dims[1]));
  }
  const int i0 = static_cast<int>(std::floor(x - 0.5));
  const int j0 = static_cast<int>(std::floor(y - 0.5));
  const double fx = x - 0.5 - i0;
  const double fy = y - 0.5 - j0;
  const int i1 = wrap(i0 + 1, dims[0]);
  const int j1 = wrap(j0 + 1, dims[1]);
  const int ia = wrap(i0, dims[0]);
  const int ja = wrap(j0, dims[1]);
  return glm::mix(glm::mix(this->Texel(image, ia, ja), this->Texel(image, i1, ja), fx),
    glm::mix(this->Texel(image, ia, j1), this->Texel(image, i1, j1), fx), fy);
}

glm::dvec3 vtkMultiMaterialEnvironment::Lookup(const glm::dvec3& d) const
{
  if (this->Kind == mmv::BackgroundEnvironment)
  {
    const double length = glm::length(d);
    return mmv::mmvEnvironment(
      length > 0.0 ? d / length : d, this->ViewUp, this->Bottom, this->Top);
  }
  const glm::dvec3 e = mmv::EnvironmentFrame(d, this->Right, this->Up, this->Front);
  if (this->Kind == mmv::EquirectangularEnvironment)
  {
    return this->SampleImage(0, mmv::EquirectangularCoord(e), this->Repeat);
  }
  glm::dvec2 st;
  const int face = mmv::CubeMapFaceCoord(e, st);
  // Faces are sampled within themselves: a texel at the edge of a face is
  // clamped there (no seamless filtering), as VTK sets cube maps up.
  return this->SampleImage(face, st, false);
}

void vtkMultiMaterialEnvironment::FitLinear(glm::dvec3& mean, glm::dmat3& slope) const
{
  if (this->Kind == mmv::BackgroundEnvironment)
  {
    // mix(bottom, top, 0.5 + 0.5 w.up) is linear in w: the fit is exact.
    mean = 0.5 * (this->Bottom + this->Top);
    slope = glm::outerProduct(0.5 * (this->Top - this->Bottom), this->ViewUp);
    return;
  }
  // A texture: the order-1 spherical-harmonic projection, over many
  // antipodal directions.
  const std::vector<glm::dvec3> directions = mmv::SkyDirections(1024);
  mean = glm::dvec3(0.0);
  slope = glm::dmat3(0.0);
  for (const glm::dvec3& w : directions)
  {
    const glm::dvec3 l = this->Lookup(w);
    mean += l;
    slope += glm::outerProduct(l, w);
  }
  mean /= static_cast<double>(directions.size());
  slope *= 3.0 / static_cast<double>(directions.size());
}

vtkTexture* vtkMultiMaterialEnvironment::GetTexture() const
{
  return this->Texture;
}

bool vtkMultiMaterialEnvironment::GetGrey() const
{
  return !this->Images.empty() &&
    this->Images[0]->GetPointData()->GetScalars()->GetNumberOfComponents() < 3;
}

//------------------------------------------------------------------------------
void vtkMultiMaterialEnvironment::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  const char* kinds[] = { "background", "cube map", "equirectangular image" };
  os << indent << "Kind: " << kinds[this->Kind] << "\n";
}
