// vtkIrradianceInputCache: what makes vtkMultiMaterialVolumeMapper recompute
// the irradiance (its keys), the material samples and their version, and the
// pre-filtered data with NaN/Inf cleaned up.
#include "mmvTestScenes.h"

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkIrradianceGrid.h"
#include "vtkIrradianceInputCache.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialLightTolerance.h"
#include "vtkPointData.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

TEST(IrradianceInputCache, MaterialVersionChangesOnlyWithTheSampledValues)
{
  vtkNew<vtkIrradianceInputCache> cache;
  const double range[2] = { 0.0, 10.0 };
  cache->SampleMaterials(nullptr, range, 16);
  EXPECT_EQ(cache->GetMaterialVersion(), 1);
  ASSERT_EQ(cache->GetScattering().size(), 16u);
  for (float s : cache->GetScattering())
  {
    EXPECT_EQ(s, 0.0f); // no materials: nothing scatters
  }

  vtkNew<vtkMaterialTransferFunction> materials;
  materials->AddNode(0.0, 0.1, 0.7, 0.2, 10.0, 1.0, 0.5, 0.0);
  materials->AddNode(10.0, 0.1, 0.7, 0.2, 10.0, 3.0, 0.0, 0.0);
  cache->SampleMaterials(materials, range, 16);
  EXPECT_EQ(cache->GetMaterialVersion(), 2);
  // s falls linearly from 0.5 at 0 to 0 at 10: sample i at 10 i / 15.
  EXPECT_NEAR(cache->GetScattering()[0], 0.5f, 1e-6);
  EXPECT_NEAR(cache->GetScattering()[5], 0.5f * (1.0f - 5.0f / 15.0f), 1e-6);
  EXPECT_NEAR(cache->GetScattering()[15], 0.0f, 1e-6);

  // The same key: nothing resampled. A colour-only edit (diffuse) changes
  // the materials' time but not the samples: the irradiance stays valid.
  cache->SampleMaterials(materials, range, 16);
  EXPECT_EQ(cache->GetMaterialVersion(), 2);
  materials->AddNode(10.0, 0.1, 0.2, 0.2, 10.0, 3.0, 0.0, 0.0);
  cache->SampleMaterials(materials, range, 16);
  EXPECT_EQ(cache->GetMaterialVersion(), 2);
  // Attenuation, scattering, the range or the table size do change them.
  materials->AddNode(10.0, 0.1, 0.2, 0.2, 10.0, 2.0, 0.0, 0.0);
  cache->SampleMaterials(materials, range, 16);
  EXPECT_EQ(cache->GetMaterialVersion(), 3);
  const double wider[2] = { -10.0, 10.0 };
  cache->SampleMaterials(materials, wider, 16);
  EXPECT_EQ(cache->GetMaterialVersion(), 4);
  cache->SampleMaterials(materials, wider, 32);
  EXPECT_EQ(cache->GetMaterialVersion(), 5);
  EXPECT_EQ(cache->GetScattering().size(), 32u);
}

TEST(IrradianceInputCache, PrefilteredDataIsNormalisedAndCleanedOnce)
{
  // Values i on a 4^3 grid at the data's resolution (an exact copy), over
  // the range [0, 3]: voxel (i, j, k) holds i / 3. Voxel (1, 1, 1) is NaN,
  // then +Inf, then -Inf; its neighbours stay as they are (the copy samples
  // trilinearly, and a zero-weight tap once made them NaN: 0 * Inf).
  auto image = mmvtest::MakeVolume(4, [](int i, int, int) { return static_cast<float>(i); });
  auto* values = vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars());
  const int dims[3] = { 4, 4, 4 };
  const double range[2] = { 0.0, 3.0 };
  vtkNew<vtkIrradianceInputCache> cache;
  const float nonFinite[3] = { std::numeric_limits<float>::quiet_NaN(),
    std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity() };
  const float cleaned[3] = { 0.0f, 1.0f, 0.0f }; // NaN: empty; +-Inf: the range's ends
  constexpr int Middle = 1 + 4 * (1 + 4 * 1);    // voxel (1, 1, 1)
  for (int c = 0; c < 3; ++c)
  {
    values->SetValue(Middle, nonFinite[c]);
    EXPECT_TRUE(cache->UpdatePrefiltered(image, values, nullptr, dims, 10 + c, range))
      << "non-finite values are reported";
    EXPECT_EQ(cache->GetPrefilteredVersion(), static_cast<unsigned long>(c + 1));
    const std::vector<float>& v = cache->GetPrefiltered();
    ASSERT_EQ(v.size(), 64u);
    EXPECT_EQ(v[Middle], cleaned[c]) << "case " << c;
    for (int id = 0; id < 64; ++id)
    {
      if (id != Middle)
      {
        EXPECT_FLOAT_EQ(v[id], static_cast<float>(id % 4) / 3.0f)
          << "case " << c << " voxel " << id;
      }
    }
  }
  // The same grid, data time and range: kept, and nothing reported again.
  EXPECT_FALSE(cache->UpdatePrefiltered(image, values, nullptr, dims, 12, range));
  EXPECT_EQ(cache->GetPrefilteredVersion(), 3u);
  // Finite data at a new time: pre-filtered again, nothing to report.
  values->SetValue(Middle, 3.0f);
  EXPECT_FALSE(cache->UpdatePrefiltered(image, values, nullptr, dims, 13, range));
  EXPECT_EQ(cache->GetPrefilteredVersion(), 4u);
  EXPECT_FLOAT_EQ(cache->GetPrefiltered()[Middle], 1.0f);
  // A coarser grid or another range: pre-filtered again.
  const int coarse[3] = { 2, 2, 2 };
  cache->UpdatePrefiltered(image, values, nullptr, coarse, 13, range);
  EXPECT_EQ(cache->GetPrefilteredVersion(), 5u);
  EXPECT_EQ(cache->GetPrefiltered().size(), 8u);
  const double wider[2] = { 0.0, 6.0 };
  cache->UpdatePrefiltered(image, values, nullptr, coarse, 13, wider);
  EXPECT_EQ(cache->GetPrefilteredVersion(), 6u);
}

TEST(IrradianceInputCache, PrefilteredVersionNamesTheValues)
{
  // A pipeline that executed again hands over the same values at a new data
  // time: pre-filtered again, but the version (which the irradiance pass
  // trusts instead of comparing the values) is kept.
  auto image = mmvtest::MakeVolume(4, [](int i, int, int) { return static_cast<float>(i); });
  vtkDataArray* values = image->GetPointData()->GetScalars();
  const int dims[3] = { 4, 4, 4 };
  const double range[2] = { 0.0, 3.0 };
  vtkNew<vtkIrradianceInputCache> cache;
  cache->UpdatePrefiltered(image, values, nullptr, dims, 10, range);
  EXPECT_EQ(cache->GetPrefilteredVersion(), 1u);
  cache->UpdatePrefiltered(image, values, nullptr, dims, 11, range);
  EXPECT_EQ(cache->GetPrefilteredVersion(), 1u);
  // The same values on a moved grid are other pre-filtered data.
  image->SetOrigin(1.0, 0.0, 0.0);
  cache->UpdatePrefiltered(image, values, nullptr, dims, 12, range);
  EXPECT_EQ(cache->GetPrefilteredVersion(), 2u);
}

TEST(IrradianceInputCache, StoredIrradianceIsCurrentUntilItsInputsChange)
{
  vtkNew<vtkIrradianceInputCache> cache;
  vtkIrradianceInputCache::VolumeKey volume;
  volume.DataTime = 10;
  volume.Range[1] = 1.0;
  volume.NumberOfLights = 1;
  volume.Cut = { 1.0, 2.0 };
  std::vector<mmv::LightSource> lights(1);
  const int dims[3] = { 8, 8, 8 };
  EXPECT_FALSE(cache->IsCurrent(volume, lights, dims, 0.0)) << "nothing stored yet";
  EXPECT_FALSE(cache->SameVolume(volume));
  cache->Store(volume, lights, dims);
  EXPECT_TRUE(cache->IsCurrent(volume, lights, dims, 0.0));

  // A moved light or another grid: not current, but the same volume (an
  // interactive frame may keep the irradiance).
  std::vector<mmv::LightSource> moved = lights;
  moved[0].ToLight = glm::dvec3(1.0, 0.0, 0.0);
  EXPECT_FALSE(cache->IsCurrent(volume, moved, dims, 0.0));
  const int finer[3] = { 16, 8, 8 };
  EXPECT_FALSE(cache->IsCurrent(volume, lights, finer, 0.0));
  EXPECT_TRUE(cache->SameVolume(volume));

  // Any field of the volume key makes it another volume.
  vtkIrradianceInputCache::VolumeKey other = volume;
  other.Cut[1] = 3.0;
  EXPECT_FALSE(cache->SameVolume(other));
  other = volume;
  other.OpacityTime = 11;
  EXPECT_FALSE(cache->SameVolume(other));
  other = volume;
  other.MultipleScattering = true;
  EXPECT_FALSE(cache->SameVolume(other));
  other = volume;
  other.UnitDistance = std::nan("");
  EXPECT_FALSE(cache->SameVolume(other)) << "a NaN never matches: recomputed every frame";

  // Released graphics resources or a failed computation: recompute.
  cache->Invalidate();
  EXPECT_FALSE(cache->SameVolume(volume));
  EXPECT_FALSE(cache->IsCurrent(volume, lights, dims, 0.0));
}

TEST(IrradianceInputCache, LightsWithinTheToleranceKeepTheStoredIrradiance)
{
  vtkNew<vtkIrradianceInputCache> cache;
  vtkIrradianceInputCache::VolumeKey volume;
  volume.NumberOfLights = 2;
  std::vector<mmv::LightSource> lights(2);
  lights[1].Kind = mmv::PointLight;
  lights[1].Position = glm::dvec3(100.0, 0.0, 0.0);
  const int dims[3] = { 8, 8, 8 };
  cache->Store(volume, lights, dims);

  // ParaView's kit differs in the last bits between its first renders: the
  // rounding floor keeps the irradiance even with tolerance 0.
  std::vector<mmv::LightSource> rounded = lights;
  rounded[0].ToLight = glm::normalize(glm::dvec3(1e-15, 0.0, 1.0));
  EXPECT_TRUE(cache->IsCurrent(volume, rounded, dims, 0.0));
  rounded[0].ToLight = glm::normalize(glm::dvec3(1e-5, 0.0, 1.0));
  EXPECT_FALSE(cache->IsCurrent(volume, rounded, dims, 0.0));

  // A directional light turned by 0.5 degrees, tolerance 1 degree: kept;
  // by 1.5 degrees: recomputed.
  const double one = mmv::LightToleranceRadians(1.0);
  auto turned = [&](double degrees)
  {
    std::vector<mmv::LightSource> l = lights;
    const double a = glm::radians(degrees);
    l[0].ToLight = glm::dvec3(std::sin(a), 0.0, std::cos(a));
    return l;
  };
  EXPECT_TRUE(cache->IsCurrent(volume, turned(0.5), dims, one));
  EXPECT_FALSE(cache->IsCurrent(volume, turned(1.5), dims, one));

  // A point light: the angle its move subtends at the grid's centre.
  const mmv::IrradianceGrid& g = cache->GetGrid();
  const glm::dvec3 centre =
    g.IndexToPhysical(0.5 * (glm::dvec3(g.Dimensions[0], g.Dimensions[1], g.Dimensions[2]) - 1.0));
  const double distance = glm::length(lights[1].Position - centre);
  std::vector<mmv::LightSource> shifted = lights;
  shifted[1].Position.y += 0.9 * one * distance;
  EXPECT_TRUE(cache->IsCurrent(volume, shifted, dims, one));
  shifted[1].Position.y += 0.2 * one * distance;
  EXPECT_FALSE(cache->IsCurrent(volume, shifted, dims, one));

  // Anything but the placement must match exactly.
  std::vector<mmv::LightSource> attenuated = lights;
  attenuated[1].Attenuation.y = 1e-9;
  EXPECT_FALSE(cache->IsCurrent(volume, attenuated, dims, mmv::LightToleranceRadians(45.0)));
  std::vector<mmv::LightSource> kind = lights;
  kind[0].Kind = mmv::PointLight;
  EXPECT_FALSE(cache->IsCurrent(volume, kind, dims, mmv::LightToleranceRadians(45.0)));
}

TEST(IrradianceInputCache, LightToleranceDegreesAreValidated)
{
  EXPECT_EQ(mmv::LightToleranceRadians(-1.0), 0.0);
  EXPECT_EQ(mmv::LightToleranceRadians(std::nan("")), 0.0);
  EXPECT_DOUBLE_EQ(mmv::LightToleranceRadians(90.0), glm::radians(45.0));
  EXPECT_DOUBLE_EQ(mmv::LightToleranceRadians(2.0), glm::radians(2.0));
}

TEST(IrradianceInputCache, PrefilterIsTheMeanOfTrilinearFootprintSamples)
{
  // The separable pre-filter against its definition, sample by sample:
  // the mean of trilinear samples over each voxel's footprint.
  const int data[3] = { 23, 17, 12 };
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(data[0], data[1], data[2]);
  vtkNew<vtkFloatArray> values;
  values->SetNumberOfTuples(static_cast<vtkIdType>(data[0]) * data[1] * data[2]);
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
  {
    values->SetValue(i, static_cast<float>(std::sin(0.37 * i) * 50.0 + 0.01 * i));
  }
  image->GetPointData()->SetScalars(values);
  const int grids[][3] = { { 23, 17, 12 }, { 12, 9, 6 }, { 8, 17, 5 }, { 5, 4, 3 }, { 2, 2, 2 } };
  for (const auto& dims : grids)
  {
    const mmv::IrradianceGrid grid = mmv::MakeIrradianceGrid(image, dims);
    std::vector<float> separable;
    mmv::PrefilterScalars(image, values, 0, grid, separable);
    ASSERT_EQ(separable.size(), static_cast<size_t>(grid.GetNumberOfVoxels()));
    const mmv::FootprintLayout layout = mmv::MakeFootprintLayout(data, dims);
    mmv::IrradianceGrid dataGrid;
    std::copy(data, data + 3, dataGrid.Dimensions);
    double worst = 0.0;
    for (vtkIdType v = 0; v < grid.GetNumberOfVoxels(); ++v)
    {
      double sum = 0.0;
      for (int k = 0; k < layout.Samples[2]; ++k)
      {
        for (int j = 0; j < layout.Samples[1]; ++j)
        {
          for (int i = 0; i < layout.Samples[0]; ++i)
          {
            const int q[3] = { i, j, k };
            sum += mmv::SampleTrilinear(dataGrid, values->GetPointer(0),
              mmv::FootprintSample(layout, grid.IndexOfVoxel(v), q));
          }
        }
      }
      const double mean = sum / (layout.Samples[0] * layout.Samples[1] * layout.Samples[2]);
      worst = std::max(worst, std::abs(mean - separable[v]));
    }
    EXPECT_LT(worst, 1e-4) << dims[0] << "x" << dims[1] << "x" << dims[2];
    // In slabs of one to five data slices (a time step's buffers are
    // slab-sized and kept): the same values bit for bit.
    mmv::PrefilterScratch scratch;
    for (const int slices : { 1, 2, 5 })
    {
      scratch.SlabPoints = static_cast<vtkIdType>(slices) * data[0] * data[1];
      std::vector<float> slabs;
      mmv::PrefilterScalars(image, values, 0, grid, slabs, &scratch);
      EXPECT_EQ(slabs, separable) << dims[0] << "x" << dims[1] << "x" << dims[2] << ", slabs of "
                                  << slices << " slice(s)";
    }
  }
  // At the data's resolution a NaN stays on its point (weight-0 taps are
  // not read), as the trilinear interpolation keeps it.
  values->SetValue(5 + 3 * data[0] + 2 * data[0] * data[1], NAN);
  std::vector<float> copy;
  mmv::PrefilterScalars(image, values, 0, mmv::MakeIrradianceGrid(image, data), copy);
  size_t nan = 0;
  for (float v : copy)
  {
    nan += std::isnan(v) ? 1 : 0;
  }
  EXPECT_EQ(nan, 1u);
}

TEST(IrradianceInputCache, NonFiniteValuesBecomeTheFiniteRangesEnds)
{
  // One rule for the mapper (normalised, [0, 1]) and the CPU filter (data
  // units): NaN and -Inf the finite minimum, +Inf the maximum.
  const float inf = std::numeric_limits<float>::infinity();
  std::vector<float> values = { 3.0f, NAN, -inf, inf, -2.0f };
  EXPECT_TRUE(mmv::ReplaceNonFinite(values, -2.0f, 7.0f));
  const std::vector<float> expected = { 3.0f, -2.0f, -2.0f, 7.0f, -2.0f };
  EXPECT_EQ(values, expected);
  EXPECT_FALSE(mmv::ReplaceNonFinite(values, -2.0f, 7.0f));
}
