#include "image_writer.hpp"

#include "render/core/stopwatch.hpp"

namespace tetray {

ImageWriter::ImageWriter(config::Output output) : output_(std::move(output)) {
  if (output_.queue_depth > 0) thread_ = std::thread([this] { run(); });
}

ImageWriter::~ImageWriter() {
  if (!thread_.joinable()) return;
  drain();
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

void ImageWriter::submit(ImageJob job) {
  if (output_.queue_depth == 0) {
    write(job);
    return;
  }
  const render::Stopwatch waiting;
  std::unique_lock lock(mutex_);
  changed_.wait(lock,
                [&] { return queue_.size() < static_cast<std::size_t>(output_.queue_depth); });
  job.record.queue_wait_ms = waiting.ms();
  queue_.push_back(std::move(job));
  lock.unlock();
  changed_.notify_all();
}

void ImageWriter::drain() {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return queue_.empty() && !busy_; });
}

std::string ImageWriter::take_error() {
  if (!has_error()) return {};
  std::lock_guard lock(mutex_);
  std::string error = std::move(error_);
  if (later_errors_ > 0) error += " (and " + std::to_string(later_errors_) + " more writer errors)";
  error_.clear();
  later_errors_ = 0;
  has_error_.store(false, std::memory_order_release);
  return error;
}

void ImageWriter::run() {
  std::unique_lock lock(mutex_);
  for (;;) {
    changed_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
    if (queue_.empty()) return;
    ImageJob job = std::move(queue_.front());
    queue_.pop_front();
    busy_ = true;
    lock.unlock();
    changed_.notify_all();
    write(job);
    lock.lock();
    busy_ = false;
    changed_.notify_all();
  }
}

void ImageWriter::write(ImageJob& job) {
  std::string error;
  try {
    error = write_image_job(output_, job);
  } catch (const std::exception& e) {
    error = "writing step " + std::to_string(job.record.step) + " of scene " + job.record.scene +
            ": " + e.what();
  }
  if (error.empty()) return;
  std::lock_guard lock(mutex_);
  if (error_.empty()) {
    error_ = std::move(error);
  } else {
    ++later_errors_;
  }
  has_error_.store(true, std::memory_order_release);
}

}  // namespace tetray
