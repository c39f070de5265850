/**
 * The plate-and-floor scene of the shadow tests: a volume seen from above
 * (+z) and lit from above by one directional light, shaded with one ambient-
 * heavy material whose attenuation casts shadows, sampled at a fixed step
 * on the full irradiance grid.
 */
#ifndef mmvPlateScene_h
#define mmvPlateScene_h

#include "mmvTestScenes.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialVolumeMapper.h"

#include <vector>

namespace mmvtest
{

struct PlateScene : Scene
{
  vtkNew<vtkMultiMaterialVolumeMapper> Mapper;
  vtkNew<vtkMaterialTransferFunction> Materials;
  vtkSmartPointer<vtkImageData> Image;

  /// `bounds`: what the camera frames (null: the image's bounds), so that
  /// images of other grids can be framed alike.
  PlateScene(vtkImageData* image, double specular, const double* bounds = nullptr)
    : Scene(64)
    , Image(image)
  {
    this->Color->AddRGBPoint(0.0, 1.0, 0.9, 0.8);
    this->Color->AddRGBPoint(1.0, 1.0, 0.9, 0.8);
    this->Opacity->AddPoint(0.0, 0.0);
    this->Opacity->AddPoint(0.5, 0.5);
    this->Opacity->AddPoint(1.0, 0.5);
    this->Property->SetScalarOpacityUnitDistance(1.0);
    this->Materials->AddNode(1.0, 0.6, 0.4, specular, 10.0, 1.0, 0.0, 0.0);
    SetUpFullGridMapper(this->Mapper.Get(), image, this->Materials, this->Volume);
    this->FrameBounds(bounds ? bounds : image->GetBounds(), 1.1);
    const double from[3] = { 20.0, 18.0, 100.0 };
    const double to[3] = { 16.0, 16.0, 0.0 };
    this->AddDirectionalLight(from, to);
  }

  std::vector<unsigned char> Render()
  {
    this->Window->Render();
    return this->Pixels();
  }
};

} // namespace mmvtest

#endif
