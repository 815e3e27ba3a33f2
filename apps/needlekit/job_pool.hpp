// `needlekit serve`'s long runs (optimize, uncertainty): a bounded pool of worker threads with a bounded queue.
// A job reports the fraction done through its progress callback, which also stops it when the job is cancelled or
// the server is stopping (the library's progress callbacks return false: the run stops at its next check). An
// exception from a job is that job's error, never the server's. Finished jobs are kept (the last kKeptFinished) so
// that their result can be polled.
#pragma once
#include <nlohmann/json.hpp>

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace needlekit::cli {

// What a job's work function gets: report(fraction) returns false once the job should stop.
class JobProgress {
public:
  virtual ~JobProgress() = default;
  virtual bool report(double fraction) = 0;
};

// The work: returns the result as JSON; throws InvalidInput/IoError (bad input: "error" with "bad_input": true),
// Interrupted (cancelled) or anything else (an internal error of this job).
using JobWork = std::function<nlohmann::json(JobProgress&)>;

class JobPool {
public:
  static constexpr std::size_t kKeptFinished = 64;

  // workers >= 1 threads; at most `queue_limit` jobs wait for a worker.
  JobPool(int workers, std::size_t queue_limit);
  ~JobPool();  // cancels every job and joins the workers
  JobPool(const JobPool&) = delete;
  JobPool& operator=(const JobPool&) = delete;

  // The new job's id, or nullopt when the queue is full.
  std::optional<std::string> submit(std::string kind, JobWork work);
  // {"id", "kind", "state": queued|running|done|failed|cancelled, "fraction", "progress_reports", "result"?,
  // "error"?, "bad_input"?}; nullopt for an unknown id.
  std::optional<nlohmann::json> status(const std::string& id) const;
  // Asks a job to stop (a queued job never starts); false for an unknown id.
  bool cancel(const std::string& id);
  // Cancels every job; the workers end once their current job has stopped.
  void stop();

private:
  struct Job;
  void work_loop();
  void forget_old_jobs();  // under lock_

  mutable std::mutex lock_;
  std::condition_variable wake_;
  std::deque<std::shared_ptr<Job>> queue_;
  std::map<std::string, std::shared_ptr<Job>> jobs_;
  std::deque<std::string> finished_;  // ids in the order they finished
  std::size_t queue_limit_;
  std::uint64_t next_id_ = 1;
  bool stopping_ = false;
  std::vector<std::thread> workers_;
};

}  // namespace needlekit::cli
