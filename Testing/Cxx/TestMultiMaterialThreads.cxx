// mmv::RunOnAllCores: where VTK's default SMP backend is Sequential, the
// loops inside run on several threads (when the machine has more than one
// core) and the backend is restored after; a backend the user chose through
// VTK_SMP_BACKEND_IN_USE is kept. A parallel loop computes what the
// sequential one does.
#include "vtkMultiMaterialThreads.h"

#include <gtest/gtest.h>

#include <mutex>
#include <numeric>
#include <set>
#include <string>
#include <thread>
#include <vector>

namespace
{
/// The distinct threads that ran the chunks of a loop of `n` items.
size_t ThreadsOfALoop(vtkIdType n)
{
  std::mutex mutex;
  std::set<std::thread::id> threads;
  vtkSMPTools::For(0, n, 1,
    [&](vtkIdType begin, vtkIdType end)
    {
      volatile double sink = 0.0;
      for (vtkIdType i = begin; i < end; ++i)
      {
        for (int k = 0; k < 20000; ++k)
        {
          sink = sink + 1e-9 * k;
        }
      }
      std::lock_guard<std::mutex> lock(mutex);
      threads.insert(std::this_thread::get_id());
    });
  return threads.size();
}
}

TEST(MultiMaterialThreads, LoopsUseSeveralThreadsAndTheBackendIsRestored)
{
  const std::string before = vtkSMPTools::GetBackend();
  if (!mmv::ThreadsAddedToSequentialVTK())
  {
    GTEST_SKIP() << "VTK's backend here is " << before << " (or chosen by the user)";
  }
  if (std::thread::hardware_concurrency() < 2)
  {
    GTEST_SKIP() << "one core";
  }
  EXPECT_EQ(ThreadsOfALoop(256), 1u); // Sequential: the calling thread
  std::string inside;
  size_t threads = 0;
  mmv::RunOnAllCores(
    [&]()
    {
      inside = vtkSMPTools::GetBackend();
      threads = ThreadsOfALoop(256);
    });
  EXPECT_EQ(inside, "STDThread");
  EXPECT_GE(threads, 2u);
  EXPECT_EQ(std::string(vtkSMPTools::GetBackend()), before);
}

TEST(MultiMaterialThreads, AParallelSumEqualsTheSequentialOne)
{
  std::vector<double> values(1 << 20);
  std::iota(values.begin(), values.end(), 0.0);
  std::vector<double> doubled(values.size());
  mmv::RunOnAllCores(
    [&]()
    {
      vtkSMPTools::For(0, static_cast<vtkIdType>(values.size()),
        [&](vtkIdType b, vtkIdType e)
        {
          for (vtkIdType i = b; i < e; ++i)
          {
            doubled[i] = 2.0 * values[i];
          }
        });
    });
  const double sum = std::accumulate(doubled.begin(), doubled.end(), 0.0);
  const double n = static_cast<double>(values.size());
  EXPECT_DOUBLE_EQ(sum, n * (n - 1.0));
}
