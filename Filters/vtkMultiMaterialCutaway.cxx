#include "vtkMultiMaterialCutaway.h"

#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPlane.h"
#include "vtkPlaneCollection.h"
#include "vtkVolumeMapper.h"

#include <algorithm>
#include <cmath>

namespace mmv
{

std::vector<double> Cutaway::Key() const
{
  std::vector<double> key{ double(this->NumberOfPlanes), double(this->Cropping) };
  for (int p = 0; p < this->NumberOfPlanes; ++p)
  {
    key.insert(
      key.end(), { this->Planes[p].x, this->Planes[p].y, this->Planes[p].z, this->Planes[p].w });
  }
  if (this->Cropping)
  {
    key.insert(key.end(), this->CropBounds, this->CropBounds + 6);
    key.push_back(this->CropFlags);
  }
  return key;
}

Cutaway MakeCutaway(vtkVolumeMapper* mapper, const vtkMatrix4x4* worldToObject, int* dropped)
{
  if (!mapper)
  {
    if (dropped)
    {
      *dropped = 0;
    }
    return Cutaway();
  }
  return MakeCutaway(mapper->GetCropping() != 0, mapper->GetCroppingRegionPlanes(),
    mapper->GetCroppingRegionFlags(), mapper->GetClippingPlanes(), worldToObject, dropped);
}

Cutaway MakeCutaway(bool cropping, const double croppingPlanes[6], int croppingFlags,
  vtkPlaneCollection* planes, const vtkMatrix4x4* worldToObject, int* dropped)
{
  Cutaway cut;
  if (dropped)
  {
    *dropped = 0;
  }
  if (cropping)
  {
    cut.Cropping = true;
    std::copy(croppingPlanes, croppingPlanes + 6, cut.CropBounds);
    cut.CropFlags = croppingFlags;
  }
  if (!planes)
  {
    return cut;
  }
  // Object = W^-1 world: a world plane (n, o) becomes (W^T n, W^-1 o); the
  // normal's length does not matter for the sign test.
  vtkNew<vtkMatrix4x4> objectToWorld;
  if (worldToObject)
  {
    vtkMatrix4x4::Invert(worldToObject, objectToWorld);
  }
  for (int i = 0; i < planes->GetNumberOfItems(); ++i)
  {
    vtkPlane* plane = planes->GetItem(i);
    if (!plane)
    {
      continue;
    }
    if (cut.NumberOfPlanes == MaxCutPlanes)
    {
      if (dropped)
      {
        ++*dropped;
      }
      continue;
    }
    double n[3];
    double o[4];
    plane->GetNormal(n);
    plane->GetOrigin(o);
    o[3] = 1.0;
    glm::dvec3 normal(n[0], n[1], n[2]);
    glm::dvec3 origin(o[0], o[1], o[2]);
    if (worldToObject)
    {
      glm::dvec3 objectNormal(0.0);
      for (int r = 0; r < 3; ++r)
      {
        for (int c = 0; c < 3; ++c)
        {
          objectNormal[r] += objectToWorld->GetElement(c, r) * n[c];
        }
      }
      double out[4];
      const_cast<vtkMatrix4x4*>(worldToObject)->MultiplyPoint(o, out);
      normal = objectNormal;
      origin = glm::dvec3(out[0], out[1], out[2]) / (out[3] != 0.0 ? out[3] : 1.0);
    }
    cut.Planes[cut.NumberOfPlanes++] = glm::dvec4(normal, -glm::dot(normal, origin));
  }
  return cut;
}

IndexCutaway ToIndexSpace(const Cutaway& cutaway, const IrradianceGrid& grid)
{
  // object = Origin + M index, M = Direction * diag(Spacing).
  const glm::dmat3 m = grid.IndexToPhysicalMatrix();
  IndexCutaway c;
  c.NumberOfPlanes = cutaway.NumberOfPlanes;
  for (int p = 0; p < cutaway.NumberOfPlanes; ++p)
  {
    const glm::dvec3 n(cutaway.Planes[p]);
    c.Planes[p] = glm::dvec4(glm::transpose(m) * n, glm::dot(n, grid.Origin) + cutaway.Planes[p].w);
  }
  c.Cropping = cutaway.Cropping;
  if (cutaway.Cropping)
  {
    for (int a = 0; a < 3; ++a)
    {
      // Row a of M (glm is column-major: m[column][row]).
      c.CropAxes[a] = glm::dvec4(m[0][a], m[1][a], m[2][a], grid.Origin[a]);
    }
    for (int i = 0; i < 6; ++i)
    {
      c.CropBounds[i] = cutaway.CropBounds[i];
    }
    c.CropFlags = cutaway.CropFlags;
  }
  return c;
}

std::string CutawayGLSLPrelude()
{
  std::string prelude = "#define MMV_MAX_CUT_PLANES " + std::to_string(MaxCutPlanes) + "\n";
  for (const CutawayUniformInfo& u : CutawayUniformLayout)
  {
    prelude += std::string("uniform ") + u.GLSLType + " " + u.Name +
      (u.ArraySize[0] ? std::string("[") + u.ArraySize + "]" : std::string()) + "; // " +
      u.Meaning + "\n";
  }
  return prelude;
}

} // namespace mmv
