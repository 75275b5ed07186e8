// Writing finished frames on a thread of its own while the next frames compute (`wisp render`):
// the frame threads hand each picture over as a job and go on with the next frame. Jobs run one
// at a time in the order handed over; at most `depth` wait at once (handing over blocks while the
// queue is full), so the pictures waiting to be written do not pile up in memory when writing is
// slower than rendering. The first job that throws stops the writer: the jobs waiting are
// dropped, and every later hand-over and finish() rethrows its error, so a failed write ends the
// run with that error instead of being lost on the writer's thread.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

namespace wisp::render {

class FrameWriter {
 public:
  explicit FrameWriter(std::size_t depth = 1);
  // Drops the jobs still waiting and waits for the one running (an unwinding run: the error
  // that unwinds it is the one reported).
  ~FrameWriter();
  FrameWriter(const FrameWriter&) = delete;
  FrameWriter& operator=(const FrameWriter&) = delete;

  // Blocks until fewer than `depth` jobs wait (so a caller can time how long writing held it
  // up before handing over). Rethrows an earlier job's error.
  void wait_for_room();
  // Queues `job`, blocking while `depth` jobs wait. Rethrows an earlier job's error.
  void push(std::function<void()> job);
  // Runs every job queued, then rethrows the first error if any. Call once, after the last push.
  void finish();

 private:
  void run();

  std::size_t depth_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<std::function<void()>> jobs_;
  bool closing_ = false;  // no more jobs: the thread ends when the queue is empty
  std::exception_ptr error_;
  std::thread thread_;
};

}  // namespace wisp::render
