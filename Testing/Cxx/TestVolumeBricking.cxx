// Volumes longer than the largest 3D texture (docs/scaling.md): the mapper cuts them
// into bricks instead of letting VTK's upload fail and assert in
// vtkTextureObject::Bind. Runs under Xvfb with Mesa llvmpipe (3D textures of
// at most 2048 texels); the long volume adapts to the context's limit.
#include "mmvTestGlobalVolume.h"
#include "mmvTestScenes.h"
#include "mmvTestUtilities.h"

#include "vtkDoubleArray.h"
#include "vtkGlobalPrefilteredVolume.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialVolumeMapper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkTextureObject.h"
#include "vtkVolumeBricking.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>

namespace
{

// A smooth profile along x (so that a volume sampled half as densely renders
// nearly the same), constant across y and z.
float Profile(double x, double length)
{
  return static_cast<float>(60.0 + 50.0 * std::sin(6.0 * 3.14159265358979 * x / length));
}

// `points` x 6 x 6 points spanning x in [0, length], y and z in [0, 250].
vtkSmartPointer<vtkImageData> LongVolume(int points, double length)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(points, 6, 6);
  const double dx = length / (points - 1);
  image->SetSpacing(dx, 50.0, 50.0);
  vtkNew<vtkFloatArray> values;
  values->SetName("values");
  values->SetNumberOfTuples(static_cast<vtkIdType>(points) * 36);
  for (vtkIdType id = 0; id < values->GetNumberOfTuples(); ++id)
  {
    values->SetValue(id, Profile(dx * static_cast<double>(id % points), length));
  }
  image->GetPointData()->SetScalars(values);
  return image;
}

int MaxTextureSize3D()
{
  mmvtest::Scene scene(16);
  scene.Window->Render();
  return vtkTextureObject::GetMaximumTextureSize3D(
    vtkOpenGLRenderWindow::SafeDownCast(scene.Window));
}

struct Frame
{
  std::vector<unsigned char> Pixels;
  int Warnings = 0;
  int Errors = 0;
  std::string Message;
  int Bricks[3] = { 0, 0, 0 };
};

// Renders `image` framed from +z in a 256 x 64 window with `mapper`.
Frame Render(vtkImageData* image, vtkMultiMaterialVolumeMapper* mapper, double length)
{
  mmvtest::Scene scene(64);
  scene.Window->SetSize(256, 64);
  scene.Color->AddRGBPoint(0.0, 0.2, 0.4, 1.0);
  scene.Color->AddRGBPoint(120.0, 1.0, 0.8, 0.3);
  scene.Opacity->AddPoint(0.0, 0.0);
  scene.Opacity->AddPoint(120.0, 0.02);
  mmvtest::ErrorCounter counter(mapper);
  mapper->SetInputData(image);
  scene.Volume->SetMapper(mapper);
  const double bounds[6] = { 0.0, length, 0.0, 250.0, 0.0, 250.0 };
  scene.FrameBounds(bounds, 1.0);
  scene.Renderer->GetActiveCamera()->SetParallelScale(0.5 * length * 64.0 / 256.0 * 1.05);
  const double from[3] = { 0.3 * length, 900.0, 1200.0 };
  const double centre[3] = { 0.5 * length, 125.0, 125.0 };
  scene.AddDirectionalLight(from, centre);
  scene.Window->Render();
  Frame frame;
  frame.Pixels = scene.Pixels();
  frame.Warnings = counter.Warnings();
  frame.Errors = counter.Errors();
  frame.Message = counter.LastMessage();
  mapper->GetBrickPartitions(frame.Bricks);
  return frame;
}

using mmvtest::PSNR;

double MeanLevel(const std::vector<unsigned char>& pixels)
{
  double sum = 0.0;
  for (unsigned char p : pixels)
  {
    sum += p;
  }
  return pixels.empty() ? 0.0 : sum / pixels.size();
}

} // namespace

//------------------------------------------------------------------------------
TEST(VolumeBricking, PartitionsInClosedForm)
{
  const int none[3] = { 1, 1, 1 };
  int parts[3];
  // The case that aborted VTK's upload: 2100 points on llvmpipe (2048): two bricks of 1051.
  const int longX[3] = { 2100, 6, 6 };
  ASSERT_TRUE(mmv::ChooseBrickPartitions(longX, 2048, none, parts));
  EXPECT_EQ(parts[0], 2);
  EXPECT_EQ(parts[1], 1);
  EXPECT_EQ(parts[2], 1);
  EXPECT_EQ(mmv::LargestBrickPoints(2100, 2), 1051);
  // Exactly the limit fits in one texture; one point more needs two bricks.
  const int atLimit[3] = { 2048, 2048, 3 };
  ASSERT_TRUE(mmv::ChooseBrickPartitions(atLimit, 2048, none, parts));
  EXPECT_EQ(parts[0] * parts[1] * parts[2], 1);
  const int overLimit[3] = { 2049, 5000, 3 };
  ASSERT_TRUE(mmv::ChooseBrickPartitions(overLimit, 2048, none, parts));
  EXPECT_EQ(parts[0], 2);
  EXPECT_EQ(parts[1], 3); // 4999 / 2047 = 2.44 -> 3
  // Requested partitions that fit are kept; those that do not are raised.
  const int requested[3] = { 4, 1, 2 };
  ASSERT_TRUE(mmv::ChooseBrickPartitions(longX, 2048, requested, parts));
  EXPECT_EQ(parts[0], 4);
  EXPECT_EQ(parts[2], 2);
  // No texture of 2 texels holds a brick (a brick has 2 points at least).
  EXPECT_FALSE(mmv::ChooseBrickPartitions(longX, 2, none, parts));
  // A brick budget cuts the longest bricks until each fits: 640^3 floats
  // (1000 MiB) in bricks of at most 512 MiB take 2 parts along one axis.
  const int cube[3] = { 640, 640, 640 };
  ASSERT_TRUE(mmv::ChooseBrickPartitions(cube, 2048, none, parts));
  ASSERT_TRUE(mmv::LimitBrickBytes(cube, 4.0, 512.0 * 1024 * 1024, parts));
  EXPECT_EQ(parts[0] * parts[1] * parts[2], 2);
  double brick = 4.0;
  for (int a = 0; a < 3; ++a)
  {
    brick *= mmv::LargestBrickPoints(640, parts[a]);
  }
  EXPECT_LE(brick, 512.0 * 1024 * 1024);
  // 64 MiB bricks: 1000 MiB / 64 = 15.6, so at least 16 bricks, spread over the axes.
  ASSERT_TRUE(mmv::ChooseBrickPartitions(cube, 2048, none, parts));
  ASSERT_TRUE(mmv::LimitBrickBytes(cube, 4.0, 64.0 * 1024 * 1024, parts));
  EXPECT_GE(parts[0] * parts[1] * parts[2], 16);
  EXPECT_LE(parts[0] * parts[1] * parts[2], 32);
  EXPECT_LE(
    std::max({ parts[0], parts[1], parts[2] }) - std::min({ parts[0], parts[1], parts[2] }), 1);
  // Nothing fits a budget below one 2 x 2 x 2 brick.
  ASSERT_TRUE(mmv::ChooseBrickPartitions(cube, 2048, none, parts));
  EXPECT_FALSE(mmv::LimitBrickBytes(cube, 4.0, 16.0, parts));
  // For every length up to 3 limits: the bricks fit and one brick fewer
  // would not (the fewest bricks).
  for (int limit : { 16, 17, 64 })
  {
    for (int n = 2; n <= 3 * limit; ++n)
    {
      const int dims[3] = { n, 2, 2 };
      ASSERT_TRUE(mmv::ChooseBrickPartitions(dims, limit, none, parts));
      EXPECT_LE(mmv::LargestBrickPoints(n, parts[0]), limit) << n;
      if (parts[0] > 1)
      {
        EXPECT_GT(mmv::LargestBrickPoints(n, parts[0] - 1), limit) << n;
      }
    }
  }
}

//------------------------------------------------------------------------------
TEST(VolumeBricking, LongerThanLargestTextureRendersInBricks)
{
  const int limit = MaxTextureSize3D();
  ASSERT_GT(limit, 16);
  const int points = limit + 52; // 2100 on llvmpipe
  const double length = 2100.0;
  std::cout << "largest 3D texture " << limit << "; volume of " << points << " x 6 x 6 points"
            << std::endl;

  vtkNew<vtkMultiMaterialVolumeMapper> ours;
  const Frame bricked = Render(LongVolume(points, length), ours, length);
  EXPECT_EQ(bricked.Errors, 0) << bricked.Message;
  EXPECT_EQ(bricked.Bricks[0], 2);
  EXPECT_EQ(bricked.Bricks[1] * bricked.Bricks[2], 1);
  EXPECT_EQ(bricked.Warnings, 1) << "the bricking notice, once";
  EXPECT_NE(bricked.Message.find("2 x 1 x 1 bricks"), std::string::npos) << bricked.Message;
  EXPECT_TRUE(ours->GetMultiMaterialActive()) << "bricks are shaded with materials";
  int irradiance[3];
  ours->GetIrradianceDimensions(irradiance);
  EXPECT_LE(irradiance[0], limit) << "the irradiance texture fits too";
  EXPECT_GT(MeanLevel(bricked.Pixels), 5.0) << "the volume is drawn (9.6 measured)";

  // The same profile sampled half as densely fits one texture: the bricks
  // (gradient volume resampled to the limit, irradiance over the whole
  // volume) show what that unbricked render shows.
  vtkNew<vtkMultiMaterialVolumeMapper> reference;
  const int half = (points + 1) / 2;
  const Frame whole = Render(LongVolume(half, length), reference, length);
  EXPECT_EQ(whole.Bricks[0] * whole.Bricks[1] * whole.Bricks[2], 1);
  EXPECT_TRUE(reference->GetMultiMaterialActive());
  const double close = PSNR(bricked.Pixels, whole.Pixels);
  std::cout << "bricked (" << points << " points) vs unbricked render of " << half
            << " points: PSNR " << close << " dB" << std::endl;
  // Measured 40.8 dB on llvmpipe: what differs is the sampling density.
  EXPECT_GE(close, 40.0);
}

//------------------------------------------------------------------------------
TEST(VolumeBricking, VolumeThatFitsKeepsOneTexture)
{
  vtkNew<vtkMultiMaterialVolumeMapper> mapper;
  const Frame frame = Render(LongVolume(300, 2100.0), mapper, 2100.0);
  EXPECT_EQ(frame.Errors, 0) << frame.Message;
  EXPECT_EQ(frame.Bricks[0] * frame.Bricks[1] * frame.Bricks[2], 1);
  EXPECT_TRUE(mapper->GetMultiMaterialActive());
}

//------------------------------------------------------------------------------
namespace
{
// A plate-and-floor scene: a plate (y 22..25, x and z 8..24) above a floor (y 2..6)
// in a 33^3 volume, lit from above: the plate's shadow falls on the floor.
float PlateAndFloor(int i, int j, int k)
{
  const bool plate = j >= 22 && j <= 25 && i >= 8 && i <= 24 && k >= 8 && k <= 24;
  const bool floor = j >= 2 && j <= 6;
  return plate || floor ? 100.0f : 0.0f;
}

struct Shaded
{
  std::vector<unsigned char> Pixels;
  bool Active = false;
  int Warnings = 0;
  int Errors = 0;
  int Bricks[3] = { 0, 0, 0 };
  std::string Source;      // the last fragment shader
  std::string LastMessage; // the last warning or error
};

// Renders `input` (the plate and floor) lit from above, after `setup` had the
// mapper.
Shaded RenderPlateAndFloorWith(
  vtkImageData* input, const std::function<void(vtkMultiMaterialVolumeMapper*)>& setup)
{
  mmvtest::Scene scene(96);
  scene.Color->AddRGBPoint(0.0, 0.9, 0.85, 0.8);
  scene.Color->AddRGBPoint(100.0, 0.9, 0.85, 0.8);
  scene.Opacity->AddPoint(0.0, 0.0);
  scene.Opacity->AddPoint(100.0, 0.8);
  vtkNew<vtkMaterialTransferFunction> materials;
  materials->AddNode(50.0, 0.2, 0.7, 0.3, 20.0, 1.0, 0.3, 0.0);
  vtkNew<vtkMultiMaterialVolumeMapper> mapper;
  mmvtest::ErrorCounter counter(mapper);
  mapper->SetInputData(input);
  mapper->SetMaterialTransferFunction(materials);
  setup(mapper);
  scene.Volume->SetMapper(mapper);
  const double bounds[6] = { 0, 32, 0, 32, 0, 32 };
  scene.FrameBounds(bounds);
  // Seen from the front and a little above, so the floor shows.
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  camera->SetPosition(16.0, 60.0, 200.0);
  scene.Renderer->ResetCameraClippingRange(const_cast<double*>(bounds));
  const double from[3] = { 20.0, 100.0, 16.0 };
  const double centre[3] = { 16.0, 16.0, 16.0 };
  scene.AddDirectionalLight(from, centre);
  scene.Window->Render();
  scene.Window->Render(); // VTK partitions the texture during the first frame
  Shaded result;
  mapper->GetBrickPartitions(result.Bricks);
  result.Pixels = scene.Pixels();
  result.Active = mapper->GetMultiMaterialActive();
  result.Warnings = counter.Warnings();
  result.Errors = counter.Errors();
  result.Source = mapper->GetLastFragmentShaderSource();
  result.LastMessage = counter.LastMessage();
  return result;
}

Shaded RenderPlateAndFloor(
  int px, int py, int pz, vtkImageData* input = nullptr, double maxBrickMB = 0.0)
{
  auto volume = mmvtest::MakeVolume(33, PlateAndFloor);
  return RenderPlateAndFloorWith(input ? input : volume.Get(),
    [&](vtkMultiMaterialVolumeMapper* m)
    {
      if (maxBrickMB > 0.0)
      {
        m->SetMaxBrickMB(maxBrickMB);
      }
      if (px * py * pz > 1)
      {
        m->SetPartitions(px, py, pz);
      }
    });
}
} // namespace

TEST(VolumeBricking, PartitionsShadeLikeTheWholeVolume)
{
  const Shaded whole = RenderPlateAndFloor(1, 1, 1);
  ASSERT_TRUE(whole.Active);
  EXPECT_GT(MeanLevel(whole.Pixels), 10.0);
  for (const auto& p : std::vector<std::array<int, 3>>{ { 2, 2, 2 }, { 3, 1, 2 }, { 1, 4, 1 } })
  {
    const Shaded bricks = RenderPlateAndFloor(p[0], p[1], p[2]);
    const double value = PSNR(whole.Pixels, bricks.Pixels);
    std::cout << "SetPartitions(" << p[0] << ", " << p[1] << ", " << p[2]
              << ") vs one texture: PSNR " << value << " dB" << std::endl;
    EXPECT_TRUE(bricks.Active) << "multi-material shading of the bricks";
    EXPECT_EQ(bricks.Warnings + bricks.Errors, 0);
    EXPECT_GE(value, 40.0);
  }
}

TEST(VolumeBricking, BrickBudgetBricksLargeTextures)
{
  // The plate and floor at 65^3 in doubles: 2.2 MB of data, 1.6 MB of
  // gradient volume. MaxBrickMB 2 bricks the data texture by itself (a
  // refused allocation would abort in VTK) and keeps the gradient whole.
  auto volume = vtkSmartPointer<vtkImageData>::New();
  volume->SetDimensions(65, 65, 65);
  volume->SetSpacing(0.5, 0.5, 0.5);
  vtkNew<vtkDoubleArray> values;
  values->SetNumberOfTuples(65 * 65 * 65);
  for (vtkIdType id = 0; id < values->GetNumberOfTuples(); ++id)
  {
    values->SetValue(
      id, PlateAndFloor(int(id % 65) / 2, int((id / 65) % 65) / 2, int(id / 4225) / 2));
  }
  volume->GetPointData()->SetScalars(values);
  const Shaded whole = RenderPlateAndFloor(1, 1, 1, volume);
  const Shaded budget = RenderPlateAndFloor(1, 1, 1, volume, 2.0);
  const double value = PSNR(whole.Pixels, budget.Pixels);
  std::cout << "MaxBrickMB 2: " << budget.Bricks[0] << " x " << budget.Bricks[1] << " x "
            << budget.Bricks[2] << " bricks, PSNR " << value << " dB vs one texture" << std::endl;
  EXPECT_EQ(whole.Bricks[0] * whole.Bricks[1] * whole.Bricks[2], 1);
  EXPECT_GE(budget.Bricks[0] * budget.Bricks[1] * budget.Bricks[2], 2);
  EXPECT_TRUE(budget.Active);
  EXPECT_EQ(budget.Errors, 0);
  EXPECT_EQ(budget.Warnings, 1) << "the bricking notice";
  EXPECT_GE(value, 40.0);
}

//------------------------------------------------------------------------------
namespace
{
// The global volume of `image` as one piece (what mmv::ExchangeGlobalPrefilter
// makes of one rank's data).
vtkSmartPointer<vtkGlobalPrefilteredVolume> GlobalVolumeOf(vtkImageData* image)
{
  auto global = vtkSmartPointer<vtkGlobalPrefilteredVolume>::New();
  mmvtest::CombinePieces({ image }, global);
  return global;
}
}

TEST(VolumeBricking, TintedShadowsFromTheGlobalVolumeEqualTheWholeVolumes)
{
  // The tint marches the global pre-filtered values, as the grey shadows do:
  // the whole volume lit from its own global volume (one piece) renders the
  // same bytes as without one, with the RGB variant in both and no warning.
  // (Across ranks: PVBatchMPIShadowsTinted3.)
  auto volume = mmvtest::MakeVolume(33, PlateAndFloor);
  vtkSmartPointer<vtkGlobalPrefilteredVolume> global = GlobalVolumeOf(volume);
  ASSERT_TRUE(global->GetValid());
  auto tinted = [&](vtkGlobalPrefilteredVolume* g)
  {
    return RenderPlateAndFloorWith(volume,
      [&](vtkMultiMaterialVolumeMapper* m)
      {
        m->SetIrradianceScale(1.0);
        m->GetMaterialTransferFunction()->RemoveAllNodes();
        m->GetMaterialTransferFunction()->AddNode(
          50.0, 0.2, 0.7, 0.3, 20.0, 1.0, 0.3, 0.0, 0.0, 0.0, 1.0, 0.6, 0.3);
        m->SetGlobalPrefilteredVolume(g);
      });
  };
  const Shaded alone = tinted(nullptr);
  const Shaded lit = tinted(global);
  for (const Shaded* s : { &alone, &lit })
  {
    EXPECT_TRUE(s->Active);
    EXPECT_NE(s->Source.find("#define MMV_USE_RGB_IRRADIANCE 1"), std::string::npos);
    EXPECT_EQ(s->Warnings + s->Errors, 0) << s->LastMessage;
  }
  ASSERT_EQ(alone.Pixels.size(), lit.Pixels.size());
  int differing = 0;
  for (size_t i = 0; i < alone.Pixels.size(); ++i)
  {
    differing += alone.Pixels[i] != lit.Pixels[i] ? 1 : 0;
  }
  EXPECT_EQ(differing, 0);
  // The tint shows: red (T = 1) is left, blue (T = 0.3) dimmed in the shadow.
  const Shaded grey = RenderPlateAndFloorWith(volume,
    [&](vtkMultiMaterialVolumeMapper* m)
    {
      m->SetIrradianceScale(1.0);
      m->SetGlobalPrefilteredVolume(global);
    });
  double redShift = 0.0;
  double blueShift = 0.0;
  for (size_t i = 0; i + 2 < lit.Pixels.size(); i += 3)
  {
    redShift += int(lit.Pixels[i]) - int(grey.Pixels[i]);
    blueShift += int(lit.Pixels[i + 2]) - int(grey.Pixels[i + 2]);
  }
  std::cout << "tinted minus grey, summed over the image: red " << redShift << ", blue "
            << blueShift << std::endl;
  EXPECT_LT(blueShift, redShift - 1000.0);
}

TEST(VolumeBricking, PieceLitFromTheGlobalVolumeShowsTheOtherPiecesShadow)
{
  // The plate and floor split as two MPI ranks would split them (y 0..14 and
  // 14..32, sharing y = 14), combined by hand as mmv::ExchangeGlobalPrefilter
  // combines them. The floor's piece alone, lit from the global volume, must
  // show the plate's shadow as the whole volume cropped to that piece does.
  auto whole = mmvtest::MakeVolume(33, PlateAndFloor);
  auto piece = [&](int y0, int y1)
  {
    auto p = vtkSmartPointer<vtkImageData>::New();
    p->SetExtent(0, 32, y0, y1, 0, 32);
    vtkNew<vtkFloatArray> values;
    values->SetNumberOfTuples(p->GetNumberOfPoints());
    vtkIdType id = 0;
    for (int k = 0; k <= 32; ++k)
    {
      for (int j = y0; j <= y1; ++j)
      {
        for (int i = 0; i <= 32; ++i)
        {
          values->SetValue(id++, PlateAndFloor(i, j, k));
        }
      }
    }
    p->GetPointData()->SetScalars(values);
    return p;
  };
  auto floorPiece = piece(0, 14);
  auto platePiece = piece(14, 32);
  vtkNew<vtkGlobalPrefilteredVolume> global;
  ASSERT_TRUE(mmvtest::CombinePieces({ floorPiece, platePiece }, global));

  auto render = [&](vtkImageData* input, vtkGlobalPrefilteredVolume* g)
  {
    const Shaded shaded = RenderPlateAndFloorWith(input,
      [&](vtkMultiMaterialVolumeMapper* m)
      {
        m->SetIrradianceScale(1.0);
        m->SetGlobalPrefilteredVolume(g);
      });
    EXPECT_TRUE(shaded.Active);
    return shaded.Pixels;
  };
  // The reference: the floor piece lit from a global volume made of the
  // whole volume as one piece. (The whole volume cropped to the floor piece
  // was the reference before cutaways: cropped parts now cast no shadow.)
  vtkSmartPointer<vtkGlobalPrefilteredVolume> single = GlobalVolumeOf(whole);
  ASSERT_TRUE(single->GetValid());
  const auto cropped = render(floorPiece, single);
  const auto withGlobal = render(floorPiece, global);
  const auto alone = render(floorPiece, nullptr);
  const double lit = PSNR(cropped, withGlobal);
  const double unlit = PSNR(cropped, alone);
  std::cout << "floor piece lit from the pieces' global volume vs from the whole one: PSNR " << lit
            << " dB lit from the global volume, " << unlit << " dB lit alone" << std::endl;
  EXPECT_GE(lit, 40.0);
  EXPECT_LT(unlit, 35.0) << "without the global volume the plate's shadow is missing";
  EXPECT_LT(MeanLevel(withGlobal), MeanLevel(alone)) << "the shadow darkens the floor";
}
