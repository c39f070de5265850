#include "vtkMultiMaterialThreads.h"

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>

namespace
{
thread_local bool InsideJob = false;

// Workers that wait for the next loop instead of ending with each one.
class WorkerPool
{
public:
  ~WorkerPool()
  {
    {
      std::lock_guard<std::mutex> lock(this->Mutex);
      this->Stopping = true;
    }
    this->Wake.notify_all();
    for (std::thread& worker : this->Workers)
    {
      worker.join();
    }
  }

  void Run(int threads, vtkIdType chunks, const std::function<void(vtkIdType)>& job)
  {
    std::lock_guard<std::mutex> turn(this->Turn);
    const int helpers = static_cast<int>(std::min<vtkIdType>(threads, chunks)) - 1;
    {
      std::unique_lock<std::mutex> lock(this->Mutex);
      while (static_cast<int>(this->Workers.size()) < helpers)
      {
        this->Workers.emplace_back([this]() { this->Work(); });
      }
      this->Job = &job;
      this->Threads = threads;
      this->Chunks = chunks;
      this->Next = 0;
      this->Helpers = helpers;
      this->Busy = helpers;
      ++this->Generation;
    }
    this->Wake.notify_all();
    this->RunChunksOfJob(job, chunks);
    std::unique_lock<std::mutex> lock(this->Mutex);
    this->Finished.wait(lock, [this]() { return this->Busy == 0; });
    this->Job = nullptr;
  }

private:
  void RunChunksOfJob(const std::function<void(vtkIdType)>& job, vtkIdType chunks)
  {
    InsideJob = true;
    for (vtkIdType c = this->Next++; c < chunks; c = this->Next++)
    {
      job(c);
    }
    InsideJob = false;
  }

  void Work()
  {
    unsigned long seen = 0;
    std::unique_lock<std::mutex> lock(this->Mutex);
    for (;;)
    {
      this->Wake.wait(lock, [&]() { return this->Stopping || this->Generation != seen; });
      if (this->Stopping)
      {
        return;
      }
      seen = this->Generation;
      if (this->Helpers == 0)
      {
        continue; // a loop that needs fewer workers than there are
      }
      --this->Helpers;
      const std::function<void(vtkIdType)>* job = this->Job;
      const vtkIdType chunks = this->Chunks;
      // A loop inside the job runs on this thread (RunChunks).
      mmv::AllCoresThreads() = this->Threads;
      lock.unlock();
      this->RunChunksOfJob(*job, chunks);
      lock.lock();
      if (--this->Busy == 0)
      {
        this->Finished.notify_one();
      }
    }
  }

  std::mutex Turn; // one loop at a time
  std::mutex Mutex;
  std::condition_variable Wake;
  std::condition_variable Finished;
  std::vector<std::thread> Workers;
  const std::function<void(vtkIdType)>* Job = nullptr;
  int Threads = 0;
  vtkIdType Chunks = 0;
  std::atomic<vtkIdType> Next{ 0 };
  int Helpers = 0; // workers still to join the current loop
  int Busy = 0;    // workers in the current loop, not yet done
  unsigned long Generation = 0;
  bool Stopping = false;
};
}

namespace mmv
{
int& AllCoresThreads()
{
  thread_local int threads = 0;
  return threads;
}

void RunChunks(int threads, vtkIdType chunks, const std::function<void(vtkIdType)>& job)
{
  if (InsideJob || threads < 2 || chunks < 2)
  {
    for (vtkIdType c = 0; c < chunks; ++c)
    {
      job(c);
    }
    return;
  }
  static WorkerPool pool;
  pool.Run(threads, chunks, job);
}
}
