// Frame time of two volumes that shadow each other against the same scene
// built as one volume (Testing/Cxx/mmvSceneShadowsScene.h: a plate on its
// own finer grid above a floor), docs/how-it-works.md, "Several volumes in
// one view":
//
//   mmvSceneShadowsBenchmark [--size N] [--frames N]
//
// Each scene renders once (the irradiance, and for the two volumes the
// transmittance through each other), then N still frames, the two scenes
// alternating frame by frame so that machine drift hits both alike. Prints
// the first frame's seconds, the median still frame's wall seconds, the
// ratio of the medians, the transmittance's seconds and the CPU preparation
// of a still frame. Not a test: it
// asserts nothing about timings.
#include "mmvSceneShadowsScene.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace
{
using namespace mmvtest::sceneshadows;

double Seconds(ShadowScene& scene)
{
  const auto start = std::chrono::steady_clock::now();
  scene.Window->Render();
  scene.Window->WaitForCompletion();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double Median(std::vector<double> values)
{
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}
}

int main(int argc, char* argv[])
{
  int size = 512;
  int frames = 21;
  for (int i = 1; i + 1 < argc; i += 2)
  {
    if (std::strcmp(argv[i], "--size") == 0)
    {
      size = std::max(16, std::atoi(argv[i + 1]));
    }
    else if (std::strcmp(argv[i], "--frames") == 0)
    {
      frames = std::max(1, std::atoi(argv[i + 1]));
    }
  }
  ShadowScene two(size);
  SceneVolume* floor = two.Add(FloorImage());
  SceneVolume* plate = two.Add(PlateImage());
  ShadowScene one(size);
  one.Add(WholeSceneImage(
    [](double x, double y, double z) { return std::max(Floor(x, y, z), Plate(x, y, z)); }));
  for (ShadowScene* scene : { &two, &one })
  {
    scene->Renderer->ResetCameraClippingRange(-50.0, 80.0, -50.0, 80.0, -20.0, 40.0);
  }
  const double firstTwo = Seconds(two);
  const double firstOne = Seconds(one);
  std::vector<double> stillTwo;
  std::vector<double> stillOne;
  for (int f = 0; f < frames; ++f)
  {
    if (f % 2 == 0)
    {
      stillTwo.push_back(Seconds(two));
      stillOne.push_back(Seconds(one));
    }
    else
    {
      stillOne.push_back(Seconds(one));
      stillTwo.push_back(Seconds(two));
    }
  }
  const double medianTwo = Median(stillTwo);
  const double medianOne = Median(stillOne);
  std::printf("renderer: %s, %d x %d pixels, %d still frames each\n",
    mmvtest::RendererString(two.Window).c_str(), size, size, frames);
  std::printf("first frame: two volumes %.4f s, one volume %.4f s\n", firstTwo, firstOne);
  std::printf("transmittance through the other volume: floor %.4f s, plate %.4f s\n",
    floor->Mapper->GetLastSceneShadowSeconds(), plate->Mapper->GetLastSceneShadowSeconds());
  std::printf("still frame (median): two volumes %.4f s, one volume %.4f s, ratio %.3f\n",
    medianTwo, medianOne, medianTwo / medianOne);
  // The CPU preparation of the last still frame (the other volumes gathered
  // and their keys compared included).
  std::printf("preparation of the last still frame: floor %.5f s + plate %.5f s, one volume "
              "%.5f s\n",
    floor->Mapper->GetLastPrepareSeconds(), plate->Mapper->GetLastPrepareSeconds(),
    one.Volumes[0]->Mapper->GetLastPrepareSeconds());
  return 0;
}
