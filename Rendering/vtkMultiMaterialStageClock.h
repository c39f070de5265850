/**
 * @file   vtkMultiMaterialStageClock.h
 * @brief  Wall-clock seconds between the named marks of one pass through a
 *         sequence of stages, reported as "name 0.000 s, ...".
 *
 * The mapper marks its CPU preparation with it (input, tables, gradient,
 * lights, irradiance, sky, shading), so a benchmark can say where a time
 * step or an edit goes without a profiler. GPU work a stage only queues is
 * not in its seconds.
 */
#ifndef vtkMultiMaterialStageClock_h
#define vtkMultiMaterialStageClock_h

#include <chrono>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace mmv
{

class StageClock
{
public:
  /// Forgets the last pass's stages and starts timing the first.
  void Start()
  {
    this->Stages.clear();
    this->Last = Clock::now();
  }
  /// The stage that ends now.
  void Mark(const char* stage)
  {
    const Clock::time_point now = Clock::now();
    this->Stages.emplace_back(stage, std::chrono::duration<double>(now - this->Last).count());
    this->Last = now;
  }
  std::string Report() const
  {
    std::string text;
    for (const auto& stage : this->Stages)
    {
      char line[96];
      std::snprintf(
        line, sizeof(line), "%s%s %.4f s", text.empty() ? "" : ", ", stage.first, stage.second);
      text += line;
    }
    return text;
  }

private:
  using Clock = std::chrono::steady_clock;
  Clock::time_point Last = Clock::now();
  std::vector<std::pair<const char*, double>> Stages;
};

} // namespace mmv

#endif
