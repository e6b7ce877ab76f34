#include "adaptor/output/image_writer.hpp"

#include "adaptor/output/line_file.hpp"
#include "adaptor/step/thread_budget.hpp"

namespace tetray {

std::string movie_path(const std::string& directory, const std::string& scene,
                       std::int64_t first_step) {
  return image_path(directory, scene, first_step, "mp4");
}

ImageWriter::ImageWriter(config::Output output, int budget)
    : output_(std::move(output)),
      arena_(output_.writer_threads > 0 ? output_.writer_threads : writer_thread_share(budget), 1,
             tbb::task_arena::priority::low) {
  if (output_.queue_depth > 0) thread_ = std::thread([this] { run(); });
}

ImageWriter::~ImageWriter() {
  finish();
  if (!thread_.joinable()) return;
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

void ImageWriter::wait_for_room() {
  if (output_.queue_depth == 0) return;
  std::unique_lock lock(mutex_);
  changed_.wait(lock,
                [&] { return queued_images_ < static_cast<std::size_t>(output_.queue_depth); });
}

void ImageWriter::submit(ImageJob job) {
  Task task(std::move(job));
  if (output_.queue_depth == 0) {
    perform(task);
    return;
  }
  wait_for_room();
  {
    std::lock_guard lock(mutex_);
    queue_.push_back(std::move(task));
    ++queued_images_;
  }
  changed_.notify_all();
}

void ImageWriter::log_rows(std::vector<StepRecord> rows) {
  Task task(std::move(rows));
  if (output_.queue_depth == 0) {
    perform(task);
    return;
  }
  {
    std::lock_guard lock(mutex_);
    queue_.push_back(std::move(task));
  }
  changed_.notify_all();
}

void ImageWriter::drain() {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return queue_.empty() && !busy_; });
}

void ImageWriter::finish() {
  drain();
  for (auto& [scene, movie] : movies_) {
    const render::WriteResult closed = movie->close();
    if (!closed.ok) keep_error(closed.message);
  }
  movies_.clear();
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
    Task task = std::move(queue_.front());
    queue_.pop_front();
    if (std::holds_alternative<ImageJob>(task)) --queued_images_;
    busy_ = true;
    lock.unlock();
    changed_.notify_all();
    perform(task);
    lock.lock();
    busy_ = false;
    changed_.notify_all();
  }
}

// The scene's movie (created at its first frame) gets the image as written, background under it.
std::string ImageWriter::append_to_movie(const ImageJob& job) {
  std::unique_ptr<render::MovieWriter>& movie = movies_[job.record.scene];
  if (!movie) {
    std::string error;
    movie = render::MovieWriter::create(
        movie_path(output_.directory, job.record.scene, job.record.step), job.image.width,
        job.image.height, output_.movie, error);
    if (!movie) {
      movies_.erase(job.record.scene);  // tried again at the scene's next image
      return error;
    }
  }
  const render::WriteResult appended = movie->append(job.image);
  if (appended.ok) return {};
  // A frame torn in the file: the movie is not kept, and the scene's next image starts another.
  movies_.erase(job.record.scene);
  return appended.message;
}

void ImageWriter::perform(Task& task) {
  if (ImageJob* job = std::get_if<ImageJob>(&task)) {
    write(*job);
  } else {
    append_log_rows(std::get<std::vector<StepRecord>>(task));
  }
}

void ImageWriter::write(ImageJob& job) {
  std::string error;
  bool written = false;
  try {
    arena_.execute([&] {
      error = write_image_job(output_, job);
      written = error.empty();
      if (written && output_.mp4) error = append_to_movie(job);
    });
  } catch (const std::exception& e) {
    error = "writing step " + std::to_string(job.record.step) + " of scene " + job.record.scene +
            ": " + e.what();
  }
  written_.push_back(written ? std::optional<StepRecord>(job.record) : std::nullopt);
  if (!error.empty()) keep_error(std::move(error));
}

// Row k belongs to the k-th image written since the last rows; it takes the figures of the
// writer's own work on that image. The first failed append ends the step's rows.
void ImageWriter::append_log_rows(std::vector<StepRecord>& rows) {
  std::string error;
  try {
    for (std::size_t k = 0; k < rows.size() && k < written_.size() && error.empty(); ++k) {
      if (!written_[k]) continue;
      StepRecord& row = rows[k];
      row.hits = written_[k]->hits;
      row.encode_ms = written_[k]->encode_ms;
      row.write_ms = written_[k]->write_ms;
      error = append_line(log_path(output_.directory), log_row(row));
    }
  } catch (const std::exception& e) {
    error = std::string("appending to the log: ") + e.what();
  }
  written_.clear();
  if (!error.empty()) keep_error(std::move(error));
}

void ImageWriter::keep_error(std::string error) {
  std::lock_guard lock(mutex_);
  if (error_.empty()) {
    error_ = std::move(error);
  } else {
    ++later_errors_;
  }
  has_error_.store(true, std::memory_order_release);
}

}  // namespace tetray
