/**
 * What mmvIrradianceBenchmark's two files share: the window that renders the
 * CT-sized scene (Bench), the helpers every mode uses, and the modes that
 * build windows of their own (mmvIrradianceBenchmarkModes.cxx): the error
 * probe, the light-direction tolerance and the light-kit orbit.
 */
#ifndef mmvIrradianceBenchmarkModes_h
#define mmvIrradianceBenchmarkModes_h

#include "mmvBenchmarkScenes.h"

#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkMultiMaterialVolumeMapper.h"
#include "vtkRenderWindow.h"
#include "vtkSmartPointer.h"

#include <chrono>
#include <string>
#include <vector>

namespace mmvirradiance
{
/// The median of `v`; NaN when it is empty.
double Median(std::vector<double> v);

/// Dimensions as "NxNxN".
std::string Join(const int v[3]);

/// The window's back buffer as an image.
vtkSmartPointer<vtkImageData> Grab(vtkRenderWindow* window);

/// Seconds of one Render of `window`.
double TimedRender(vtkRenderWindow* window);

/// One window rendering the CT-sized scene with N scene lights.
struct Bench : mmvbench::VolumeWindow
{
  std::vector<vtkSmartPointer<vtkLight>> Lights;
  double Center[3] = { 0.0, 0.0, 0.0 };
  double Turn = 0.0;

  Bench(const mmvbench::SceneSpec& scene, int size, bool ours);

  /// `count` scene lights in place of the renderer's, placed by PlaceLights.
  void SetLightCount(int count);

  /// Turns every light by a small, new angle, so all of them need updating
  /// (or to `turn`, when given).
  void PlaceLights(double turn = -1.0);

  /// Every node's scattering becomes `strength`; the rest stays.
  void SetScattering(double strength);

  /// Median seconds of `reps` frames, each after `change` (timed around
  /// Render with glFinish inside the mapper when it is ours).
  template <typename Change>
  double Frames(int reps, Change&& change, std::vector<double>* irradiance = nullptr)
  {
    std::vector<double> frames;
    for (int r = 0; r < reps; ++r)
    {
      change();
      const auto start = std::chrono::steady_clock::now();
      this->Window->Render();
      frames.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      if (irradiance && this->Ours)
      {
        irradiance->push_back(this->Ours->GetLastIrradianceSeconds());
      }
    }
    return Median(frames);
  }
};

/// A ParaView light kit in place of the bench's lights.
void UseLightKit(Bench& bench);

/// The light-direction tolerance mode; writes OUT/light_tolerance.csv.
int RunLightTolerance(const mmvbench::SceneSpec& scene, int size, const std::string& out);

/// The error-probe mode; writes OUT/error_probe.csv.
int RunErrorProbe(const std::string& head, int ctSize, int smallSize, const std::string& out,
  double bound, const std::string& scenes);

/// The light-kit orbit mode; writes OUT/lightkit_orbit_cxx.csv and
/// OUT/lightkit_still_stages.csv.
int RunLightKitOrbit(
  const mmvbench::SceneSpec& scene, int size, const std::string& out, int steps, int interactive);
} // namespace mmvirradiance

#endif
