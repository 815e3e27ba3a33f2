#include "job_pool.hpp"

#include <fmt/format.h>

#include <atomic>
#include <exception>

#include "needlekit/core/errors.hpp"
#include "needlekit/core/interrupt.hpp"

namespace needlekit::cli {

struct JobPool::Job : JobProgress {
  std::string id, kind;
  JobWork work;
  std::atomic<double> fraction = 0.0;
  std::atomic<std::uint64_t> reports = 0;  // progress reports so far: a run that streams its progress has many
  std::atomic<bool> cancel_requested = false;
  // Under the pool's lock:
  std::string state = "queued";
  nlohmann::json result;
  std::string error;
  bool bad_input = false;

  bool report(double done) override {
    fraction.store(done);
    ++reports;
    return !cancel_requested.load() && !interrupt_requested();
  }
};

JobPool::JobPool(int workers, std::size_t queue_limit) : queue_limit_(queue_limit) {
  for (int i = 0; i < workers; ++i) workers_.emplace_back([this] { work_loop(); });
}

JobPool::~JobPool() {
  stop();
  for (std::thread& worker : workers_) worker.join();
}

std::optional<std::string> JobPool::submit(std::string kind, JobWork work) {
  const std::lock_guard<std::mutex> guard(lock_);
  if (stopping_ || queue_.size() >= queue_limit_) return std::nullopt;
  auto job = std::make_shared<Job>();
  job->id = fmt::format("{}", next_id_++);
  job->kind = std::move(kind);
  job->work = std::move(work);
  jobs_[job->id] = job;
  queue_.push_back(job);
  wake_.notify_one();
  return job->id;
}

std::optional<nlohmann::json> JobPool::status(const std::string& id) const {
  const std::lock_guard<std::mutex> guard(lock_);
  const auto found = jobs_.find(id);
  if (found == jobs_.end()) return std::nullopt;
  const Job& job = *found->second;
  nlohmann::json json = {{"id", job.id}, {"kind", job.kind}, {"state", job.state}, {"fraction", job.fraction.load()},
                         {"progress_reports", job.reports.load()}};
  if (job.state == "done") json["result"] = job.result;
  if (!job.error.empty()) {
    json["error"] = job.error;
    json["bad_input"] = job.bad_input;
  }
  return json;
}

bool JobPool::cancel(const std::string& id) {
  const std::lock_guard<std::mutex> guard(lock_);
  const auto found = jobs_.find(id);
  if (found == jobs_.end()) return false;
  Job& job = *found->second;
  job.cancel_requested = true;
  if (job.state == "queued") {
    std::erase(queue_, found->second);
    job.state = "cancelled";
    finished_.push_back(job.id);
    forget_old_jobs();
  }
  return true;
}

void JobPool::stop() {
  const std::lock_guard<std::mutex> guard(lock_);
  stopping_ = true;
  for (auto& [id, job] : jobs_) job->cancel_requested = true;
  for (const auto& job : queue_) job->state = "cancelled";
  queue_.clear();
  wake_.notify_all();
}

void JobPool::forget_old_jobs() {
  while (finished_.size() > kKeptFinished) {
    jobs_.erase(finished_.front());
    finished_.pop_front();
  }
}

void JobPool::work_loop() {
  for (;;) {
    std::shared_ptr<Job> job;
    {
      std::unique_lock<std::mutex> guard(lock_);
      wake_.wait(guard, [this] { return stopping_ || !queue_.empty(); });
      if (queue_.empty()) return;  // stopping
      job = queue_.front();
      queue_.pop_front();
      job->state = "running";
    }
    std::string state = "done", error;
    bool bad_input = false;
    nlohmann::json result;
    try {
      result = job->work(*job);
      if (job->cancel_requested) state = "cancelled";
    } catch (const Interrupted&) {
      state = "cancelled";
    } catch (const InvalidInput& e) {
      state = "failed", error = e.what(), bad_input = true;
    } catch (const IoError& e) {
      state = "failed", error = e.what(), bad_input = true;
    } catch (const std::exception& e) {
      state = "failed", error = fmt::format("internal error: {}", e.what());
    } catch (...) {
      state = "failed", error = "internal error: an unknown exception";
    }
    const std::lock_guard<std::mutex> guard(lock_);
    job->state = state;
    job->error = error;
    job->bad_input = bad_input;
    if (state == "done") {
      job->result = std::move(result);
      job->fraction = 1.0;
    }
    job->work = nullptr;
    finished_.push_back(job->id);
    forget_old_jobs();
  }
}

}  // namespace needlekit::cli
