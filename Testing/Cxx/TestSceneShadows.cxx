// Shadows between several volumes of one renderer
// (Rendering/vtkMultiMaterialSceneShadows.h): a plate volume above a floor
// volume, each on its own grid, against the same scene resampled into one
// volume; the plate moved by a user matrix; hidden, removed, empty,
// overlapping volumes and volumes of other scalar types.
#include "mmvSceneShadowsScene.h"
#include "mmvTestUtilities.h"

#include "vtkIrradianceEstimator.h"
#include "vtkUnsignedShortArray.h"
#include "vtkWeakPointer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

namespace
{
using namespace mmvtest::sceneshadows;

/// Lit pixels (any channel above 0), to check that images show something.
int LitPixels(const std::vector<unsigned char>& rgb)
{
  int lit = 0;
  for (size_t i = 0; i + 2 < rgb.size(); i += 3)
  {
    lit += (rgb[i] | rgb[i + 1] | rgb[i + 2]) != 0 ? 1 : 0;
  }
  return lit;
}
}

TEST(SceneShadows, PlateShadowsTheFloorAsInOneVolume)
{
  ShadowScene two;
  SceneVolume* floor = two.Add(FloorImage());
  SceneVolume* plate = two.Add(PlateImage());
  mmvtest::ErrorCounter messages(floor->Mapper);
  messages.Watch(plate->Mapper);
  const std::vector<unsigned char> image = two.Render();
  EXPECT_EQ(messages.Warnings() + messages.Errors(), 0) << messages.LastMessage(); // apart
  EXPECT_TRUE(floor->Mapper->GetMultiMaterialActive());
  EXPECT_TRUE(plate->Mapper->GetMultiMaterialActive());
  EXPECT_EQ(floor->Mapper->GetNumberOfSceneOccluders(), 1);
  EXPECT_EQ(plate->Mapper->GetNumberOfSceneOccluders(), 1);
  const std::vector<unsigned char> reference = RenderAsOneVolume(
    [](double x, double y, double z) { return std::max(Floor(x, y, z), Plate(x, y, z)); });
  const double psnr = mmvtest::PSNR(image, reference);
  std::cout << "two volumes against one: PSNR " << psnr << " dB" << std::endl;
  EXPECT_GT(LitPixels(image), Size * Size / 2);
  EXPECT_GE(psnr, 35.0);
}

TEST(SceneShadows, ComputeDispatchesShadowAsFragmentDraws)
{
  // The final write with the other volumes' transmittance as a compute
  // shader (what a GPU runs) gives the fragment draws' image.
  std::vector<unsigned char> images[2];
  for (const int mode :
    { vtkIrradianceEstimator::FragmentDraws, vtkIrradianceEstimator::ComputeDispatches })
  {
    ShadowScene two;
    SceneVolume* floor = two.Add(FloorImage());
    SceneVolume* plate = two.Add(PlateImage());
    floor->Mapper->GetIrradianceEstimator()->SetComputeShaders(mode);
    plate->Mapper->GetIrradianceEstimator()->SetComputeShaders(mode);
    images[mode] = two.Render();
    EXPECT_EQ(floor->Mapper->GetIrradianceEstimator()->GetComputeShadersUsed(),
      mode == vtkIrradianceEstimator::ComputeDispatches);
  }
  EXPECT_GE(mmvtest::PSNR(images[0], images[1]), 50.0);
}

TEST(SceneShadows, MovedPlateShadowsAsItsResampledCopy)
{
  vtkSmartPointer<vtkMatrix4x4> matrix = MovedPlateMatrix();
  ShadowScene two;
  two.Add(FloorImage());
  SceneVolume* plate = two.Add(PlateImage());
  plate->Volume->SetUserMatrix(matrix);
  const std::vector<unsigned char> image = two.Render();
  vtkNew<vtkMatrix4x4> inverse;
  vtkMatrix4x4::Invert(matrix, inverse);
  const std::vector<unsigned char> reference = RenderAsOneVolume(
    [&inverse](double x, double y, double z)
    {
      const double world[4] = { x, y, z, 1.0 };
      double p[4];
      inverse->MultiplyPoint(world, p);
      return std::max(Floor(x, y, z), Plate(p[0], p[1], p[2]));
    });
  const double psnr = mmvtest::PSNR(image, reference);
  std::cout << "moved plate against its resampled copy: PSNR " << psnr << " dB" << std::endl;
  EXPECT_GE(psnr, 35.0);
}

TEST(SceneShadows, PointAndSpotLightsShadowAsInOneVolume)
{
  const double position[3] = { 36.0, 30.0, 45.0 };
  for (const double cone : { 180.0, 30.0 })
  {
    ShadowScene two;
    two.Add(FloorImage());
    two.Add(PlateImage());
    two.MakeLightPositional(position, cone);
    const std::vector<unsigned char> image = two.Render();
    const std::vector<unsigned char> reference = RenderAsOneVolume([](double x, double y, double z)
      { return std::max(Floor(x, y, z), Plate(x, y, z)); },
      position, cone);
    const double psnr = mmvtest::PSNR(image, reference);
    std::cout << (cone > 90.0 ? "point" : "spot") << " light, two volumes against one: PSNR "
              << psnr << " dB" << std::endl;
    EXPECT_GT(LitPixels(image), Size * Size / 8);
    EXPECT_GE(psnr, 35.0);
  }
}

TEST(SceneShadows, HiddenVolumeCastsNoShadow)
{
  const std::vector<unsigned char> alone = RenderFloorAlone();
  ShadowScene two;
  SceneVolume* floor = two.Add(FloorImage());
  SceneVolume* plate = two.Add(PlateImage());
  const std::vector<unsigned char> shadowed = two.Render();
  plate->Volume->VisibilityOff();
  const std::vector<unsigned char> hidden = two.Render();
  EXPECT_EQ(floor->Mapper->GetNumberOfSceneOccluders(), 0);
  EXPECT_GE(mmvtest::PSNR(hidden, alone), 60.0);
  EXPECT_LT(mmvtest::PSNR(shadowed, alone), 40.0); // the shadow was there
  plate->Volume->VisibilityOn();
  EXPECT_GE(mmvtest::PSNR(two.Render(), shadowed), 60.0);
}

TEST(SceneShadows, RemovedVolumeTakesItsShadowAlong)
{
  const std::vector<unsigned char> alone = RenderFloorAlone();
  ShadowScene two;
  SceneVolume* floor = two.Add(FloorImage());
  SceneVolume* plate = two.Add(PlateImage());
  two.Render();
  const int updates = floor->Mapper->GetIrradianceUpdateCount();
  two.Renderer->RemoveVolume(plate->Volume);
  EXPECT_GE(mmvtest::PSNR(two.Render(), alone), 60.0);
  EXPECT_EQ(floor->Mapper->GetIrradianceUpdateCount(), updates + 1);
  EXPECT_EQ(floor->Mapper->GetNumberOfSceneOccluders(), 0);
  // Removed volumes are not kept alive by the search for other volumes.
  vtkWeakPointer<vtkMultiMaterialVolumeMapper> floorMapper = floor->Mapper.Get();
  vtkWeakPointer<vtkVolume> plateVolume = plate->Volume.Get();
  two.Renderer->RemoveVolume(floor->Volume);
  two.Render();
  two.Volumes.clear();
  EXPECT_EQ(floorMapper, nullptr);
  EXPECT_EQ(plateVolume, nullptr);
}

TEST(SceneShadows, OnlyChangesRelight)
{
  ShadowScene two;
  SceneVolume* floor = two.Add(FloorImage());
  SceneVolume* plate = two.Add(PlateImage());
  const std::vector<unsigned char> first = two.Render();
  const int updates = floor->Mapper->GetIrradianceUpdateCount();
  const int transmittances = floor->Mapper->GetSceneShadowUpdateCount();
  const int plateUpdates = plate->Mapper->GetIrradianceUpdateCount();
  // A still frame: nothing recomputed.
  two.Render();
  EXPECT_EQ(floor->Mapper->GetIrradianceUpdateCount(), updates);
  EXPECT_EQ(floor->Mapper->GetSceneShadowUpdateCount(), transmittances);
  // Moving the plate relights the floor (and the plate, which the floor
  // shadows from below no more than before, but whose placement changed).
  plate->Volume->SetPosition(-6.0, 0.0, 0.0);
  const std::vector<unsigned char> moved = two.Render();
  EXPECT_EQ(floor->Mapper->GetIrradianceUpdateCount(), updates + 1);
  EXPECT_EQ(floor->Mapper->GetSceneShadowUpdateCount(), transmittances + 1);
  EXPECT_EQ(plate->Mapper->GetIrradianceUpdateCount(), plateUpdates + 1);
  EXPECT_LT(mmvtest::PSNR(moved, first), 40.0);
  // An opacity edit of the plate relights the floor too.
  plate->Opacity->AddPoint(1.0, 0.1);
  two.Render();
  EXPECT_EQ(floor->Mapper->GetIrradianceUpdateCount(), updates + 2);
  // Back where it was: the first image again.
  plate->Opacity->AddPoint(1.0, 0.18);
  plate->Volume->SetPosition(0.0, 0.0, 0.0);
  EXPECT_GE(mmvtest::PSNR(two.Render(), first), 60.0);
}

TEST(SceneShadows, OtherScalarTypesAndRangesShadowAlike)
{
  ShadowScene floats;
  floats.Add(FloorImage());
  floats.Add(PlateImage());
  const std::vector<unsigned char> reference = floats.Render();
  // The floor as unsigned char over [0, 200], the plate as unsigned short
  // over [0, 1000], each with its transfer functions over its range.
  auto convert = [](vtkImageData* image, vtkDataArray* out, double high)
  {
    vtkDataArray* in = image->GetPointData()->GetScalars();
    out->SetNumberOfTuples(in->GetNumberOfTuples());
    for (vtkIdType i = 0; i < in->GetNumberOfTuples(); ++i)
    {
      out->SetTuple1(i, std::round(in->GetTuple1(i) * high));
    }
    auto copy = vtkSmartPointer<vtkImageData>::New();
    copy->CopyStructure(image);
    copy->GetPointData()->SetScalars(out);
    return copy;
  };
  vtkNew<vtkUnsignedCharArray> bytes;
  vtkNew<vtkUnsignedShortArray> shorts;
  ShadowScene mixed;
  SceneVolume* floor = mixed.Add(convert(FloorImage(), bytes, 200.0), 0.0, 200.0);
  SceneVolume* plate = mixed.Add(convert(PlateImage(), shorts, 1000.0), 0.0, 1000.0);
  const std::vector<unsigned char> image = mixed.Render();
  EXPECT_EQ(floor->Mapper->GetNumberOfSceneOccluders(), 1);
  EXPECT_EQ(plate->Mapper->GetNumberOfSceneOccluders(), 1);
  const double psnr = mmvtest::PSNR(image, reference);
  std::cout << "unsigned char floor, unsigned short plate against floats: PSNR " << psnr << " dB"
            << std::endl;
  EXPECT_GE(psnr, 35.0);
}

TEST(SceneShadows, EmptyVolumeChangesNothing)
{
  ShadowScene two;
  two.Add(FloorImage());
  two.Add(PlateImage());
  const std::vector<unsigned char> reference = two.Render();
  // A third volume without points: VTK's mapper reports it and draws
  // nothing; it casts no shadow.
  vtkNew<vtkImageData> empty;
  ShadowScene three;
  SceneVolume* floor = three.Add(FloorImage());
  three.Add(PlateImage());
  SceneVolume* nothing = three.Add(empty);
  mmvtest::ErrorCounter errors(nothing->Mapper);
  const std::vector<unsigned char> image = three.Render();
  EXPECT_EQ(floor->Mapper->GetNumberOfSceneOccluders(), 1);
  EXPECT_GE(mmvtest::PSNR(image, reference), 60.0);
}

TEST(SceneShadows, VolumeInsideAnotherRenders)
{
  // The plate inside a box of thin fog that holds it: each dims the other's
  // lights (the fog counts the plate's extinction on its way up and the
  // plate the fog's above it); the two are blended, not composited in one
  // ray.
  const int dims[3] = { 17, 17, 10 };
  const double origin[3] = { 0.0, 0.0, 0.0 };
  ShadowScene nested;
  SceneVolume* fog =
    nested.Add(Sample(dims, origin, 2.0, [](double, double, double) { return 0.55; }));
  SceneVolume* plate = nested.Add(PlateImage());
  mmvtest::ErrorCounter messages(fog->Mapper);
  messages.Watch(plate->Mapper);
  const std::vector<unsigned char> image = nested.Render();
  nested.Render();
  // Each is told once that their overlap is blended, not integrated.
  EXPECT_EQ(messages.Warnings(), 2);
  EXPECT_NE(messages.LastMessage().find("overlaps another"), std::string::npos)
    << messages.LastMessage();
  EXPECT_EQ(fog->Mapper->GetNumberOfSceneOccluders(), 1);
  EXPECT_EQ(plate->Mapper->GetNumberOfSceneOccluders(), 1);
  EXPECT_TRUE(fog->Mapper->GetMultiMaterialActive());
  EXPECT_TRUE(plate->Mapper->GetMultiMaterialActive());
  EXPECT_GT(LitPixels(image), Size * Size / 2);
}

TEST(SceneShadows, VolumeAloneComputesNoTransmittance)
{
  ShadowScene alone;
  SceneVolume* floor = alone.Add(FloorImage());
  alone.Render();
  EXPECT_EQ(floor->Mapper->GetNumberOfSceneOccluders(), 0);
  EXPECT_EQ(floor->Mapper->GetSceneShadowUpdateCount(), 0);
  // A second volume drawn by the same mapper (as ParaView's vtkPVLODVolume
  // holds the volume that renders) does not shadow it.
  vtkNew<vtkVolume> twin;
  twin->SetMapper(floor->Mapper);
  twin->SetProperty(floor->Property);
  alone.Renderer->AddVolume(twin);
  alone.Render();
  EXPECT_EQ(floor->Mapper->GetNumberOfSceneOccluders(), 0);
  EXPECT_EQ(floor->Mapper->GetSceneShadowUpdateCount(), 0);
}
