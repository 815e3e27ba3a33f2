// `needlekit serve`'s job pool (apps/needlekit/job_pool.hpp): a job's exception is that job's error and the pool goes
// on serving; bad input is told apart from an internal error; a full queue refuses; a cancelled job stops at its next
// progress report; the workers are bounded.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>

#include "../../apps/needlekit/job_pool.hpp"
#include "needlekit/core/errors.hpp"
#include "needlekit/core/interrupt.hpp"

namespace needlekit::cli {
namespace {

// Polls a job until it has finished (any state but queued or running); fails the test after 30 s.
nlohmann::json finished(const JobPool& pool, const std::string& id) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  for (;;) {
    const std::optional<nlohmann::json> status = pool.status(id);
    if (!status) throw std::logic_error("unknown job " + id);
    const std::string state = (*status)["state"];
    if (state != "queued" && state != "running") return *status;
    if (std::chrono::steady_clock::now() > deadline) throw std::runtime_error("job " + id + " did not finish");
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

TEST(JobPool, AnInternalErrorIsThatJobsErrorAndThePoolGoesOn) {
  JobPool pool(1, 4);
  const auto throwing = pool.submit("optimize", [](JobProgress&) -> nlohmann::json {
    throw std::out_of_range("vector::_M_range_check: __n (which is 7) >= this->size() (which is 3)");
  });
  const auto unknown = pool.submit("optimize", [](JobProgress&) -> nlohmann::json { throw 42; });
  const auto fine = pool.submit("optimize", [](JobProgress& progress) -> nlohmann::json {
    progress.report(0.5);
    return {{"answer", 42}};
  });
  ASSERT_TRUE(throwing && unknown && fine);
  const nlohmann::json failed = finished(pool, *throwing);
  EXPECT_EQ(failed["state"], "failed");
  EXPECT_EQ(failed["error"], "internal error: vector::_M_range_check: __n (which is 7) >= this->size() (which is 3)");
  EXPECT_EQ(failed["bad_input"], false);
  EXPECT_FALSE(failed.contains("result"));
  const nlohmann::json odd = finished(pool, *unknown);
  EXPECT_EQ(odd["state"], "failed");
  EXPECT_EQ(odd["error"], "internal error: an unknown exception");
  const nlohmann::json done = finished(pool, *fine);
  EXPECT_EQ(done["state"], "done");
  EXPECT_EQ(done["result"]["answer"], 42);
  EXPECT_EQ(done["fraction"], 1.0);
  EXPECT_EQ(done["progress_reports"], 1);
}

TEST(JobPool, BadInputIsToldApartFromAnInternalError) {
  JobPool pool(1, 4);
  const auto invalid = pool.submit("patch", [](JobProgress&) -> nlohmann::json {
    throw InvalidInput("patch.json:1: key 'patch.size': '-3 mm' is not positive, expected a positive length");
  });
  const auto unreadable = pool.submit("patch", [](JobProgress&) -> nlohmann::json {
    throw IoError("upload-1.obj:3: expected 3 coordinates after 'v'");
  });
  ASSERT_TRUE(invalid && unreadable);
  const nlohmann::json refused = finished(pool, *invalid);
  EXPECT_EQ(refused["state"], "failed");
  EXPECT_EQ(refused["bad_input"], true);
  EXPECT_EQ(refused["error"], "patch.json:1: key 'patch.size': '-3 mm' is not positive, expected a positive length");
  EXPECT_EQ(finished(pool, *unreadable)["bad_input"], true);
}

TEST(JobPool, AFullQueueRefusesAndACancelledJobStopsAtItsNextReport) {
  JobPool pool(1, 1);
  std::atomic<bool> running = false;
  const auto first = pool.submit("uncertainty", [&running](JobProgress& progress) -> nlohmann::json {
    running = true;
    // A long run that reports its progress: it stops when the report says so, as the library's runs do.
    for (int step = 0;; ++step) {
      if (!progress.report(1.0 - 1.0 / (step + 2))) throw Interrupted();
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  });
  ASSERT_TRUE(first);
  while (!running) std::this_thread::yield();
  const auto queued = pool.submit("uncertainty", [](JobProgress&) -> nlohmann::json { return {{"ran", true}}; });
  ASSERT_TRUE(queued);
  EXPECT_FALSE(pool.submit("uncertainty", [](JobProgress&) -> nlohmann::json { return {}; }))
      << "a second job waiting beyond the queue limit of 1";
  EXPECT_EQ((*pool.status(*queued))["state"], "queued");
  EXPECT_TRUE(pool.cancel(*queued));
  EXPECT_TRUE(pool.cancel(*first));
  EXPECT_EQ(finished(pool, *first)["state"], "cancelled");
  const nlohmann::json never = finished(pool, *queued);
  EXPECT_EQ(never["state"], "cancelled");
  EXPECT_FALSE(never.contains("result"));
  EXPECT_FALSE(pool.cancel("no-such-job"));
  EXPECT_FALSE(pool.status("no-such-job"));
}

}  // namespace
}  // namespace needlekit::cli
