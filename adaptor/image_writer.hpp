// Takes image encoding and file writing off the solver's critical path: execute hands the
// composited image to a writer thread through a bounded queue and returns. When the queue is
// full, submit waits (an image is never dropped); a failure is kept and handed to the caller
// at its next call. Queue depth 0 writes in the calling thread (for comparison benchmarks).
#pragma once

#include <atomic>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <string>
#include <thread>

#include "config.hpp"
#include "output_files.hpp"

namespace tetray {

class ImageWriter {
 public:
  explicit ImageWriter(config::Output output);
  ~ImageWriter();  // drains, then stops the thread
  ImageWriter(const ImageWriter&) = delete;
  ImageWriter& operator=(const ImageWriter&) = delete;

  // Queues the job (or writes it, at depth 0). Records in the job how long it waited.
  void submit(ImageJob job);
  // Returns when every submitted job is written.
  void drain();

  bool has_error() const { return has_error_.load(std::memory_order_acquire); }
  // The first error since the last call (with a count of later ones); empty when none.
  std::string take_error();

 private:
  void run();
  void write(ImageJob& job);

  config::Output output_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<ImageJob> queue_;
  bool busy_ = false;
  bool stopping_ = false;
  std::string error_;
  int later_errors_ = 0;
  std::atomic<bool> has_error_{false};
  std::thread thread_;  // last: started after every member it uses
};

}  // namespace tetray
