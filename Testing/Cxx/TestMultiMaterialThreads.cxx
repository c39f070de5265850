// mmv::RunOnAllCores: where VTK's default SMP backend is Sequential, the
// loops inside run on several threads (when the machine has more than one
// core) and the backend is restored after; a backend the user chose through
// VTK_SMP_BACKEND_IN_USE is kept. A parallel loop computes what the
// sequential one does.
#include "vtkMultiMaterialThreads.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <mutex>
#include <numeric>
#include <set>
#include <string>
#include <thread>
#include <vector>

namespace
{
/// The distinct threads that ran the chunks of a loop of `n` items, through
/// mmv::For or (`vtkLoop`) vtkSMPTools::For.
std::set<std::thread::id> ThreadsOfALoop(vtkIdType n, bool vtkLoop = true)
{
  std::mutex mutex;
  std::set<std::thread::id> threads;
  const auto chunk = [&](vtkIdType begin, vtkIdType end)
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
  };
  if (vtkLoop)
  {
    vtkSMPTools::For(0, n, 1, chunk);
  }
  else
  {
    mmv::For(0, n, 1, chunk);
  }
  return threads;
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
  EXPECT_EQ(ThreadsOfALoop(256).size(), 1u); // Sequential: the calling thread
  std::string inside;
  size_t threads = 0;
  mmv::RunOnAllCores(
    [&]()
    {
      inside = vtkSMPTools::GetBackend();
      threads = ThreadsOfALoop(256).size();
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

// Inside RunOnAllCores, mmv::For runs on workers that stay between loops (no
// thread is started for the second loop); outside, on the calling thread.
TEST(MultiMaterialThreads, LoopsReuseTheSameWorkers)
{
  if (!mmv::ThreadsAddedToSequentialVTK() || std::thread::hardware_concurrency() < 2)
  {
    GTEST_SKIP() << "no threads added here";
  }
  EXPECT_EQ(ThreadsOfALoop(256, false).size(), 1u);
  std::set<std::thread::id> first, second;
  mmv::RunOnAllCores(
    [&]()
    {
      EXPECT_GE(mmv::AllCoresThreads(), 2);
      first = ThreadsOfALoop(256, false);
      second = ThreadsOfALoop(256, false);
    });
  EXPECT_EQ(mmv::AllCoresThreads(), 0);
  EXPECT_GE(first.size(), 2u);
  std::set<std::thread::id> both = first;
  both.insert(second.begin(), second.end());
  EXPECT_EQ(both.size(), first.size()) << "the second loop ran on new threads";
}

// Every item once, whatever the grain, and a loop inside a loop's chunk runs
// (on that chunk's thread) instead of waiting for the busy workers.
TEST(MultiMaterialThreads, EveryItemOnceAndNestedLoopsRun)
{
  for (const vtkIdType grain : { vtkIdType(0), vtkIdType(1), vtkIdType(7), vtkIdType(5000) })
  {
    std::vector<int> visits(1000, 0);
    std::vector<int> inner(1000 * 8, 0);
    mmv::RunOnAllCores(
      [&]()
      {
        mmv::For(0, 1000, grain,
          [&](vtkIdType b, vtkIdType e)
          {
            for (vtkIdType i = b; i < e; ++i)
            {
              ++visits[i];
              mmv::For(0, 8, 1,
                [&](vtkIdType ib, vtkIdType ie)
                {
                  for (vtkIdType k = ib; k < ie; ++k)
                  {
                    ++inner[8 * i + k];
                  }
                });
            }
          });
      });
    EXPECT_EQ(std::count(visits.begin(), visits.end(), 1), 1000) << "grain " << grain;
    EXPECT_EQ(std::count(inner.begin(), inner.end(), 1), 8000) << "grain " << grain;
  }
}
