// Takes image encoding and file writing off the solver's critical path: execute hands the
// composited image to a writer thread through a bounded queue and returns. When the queue is
// full, submit waits (an image is never dropped); a failure is kept and handed to the caller
// at its next call. Queue depth 0 writes in the calling thread (for comparison benchmarks).
//
// The log rows of a step come after its images, once execute knows its whole blocked time: the
// writer appends each row when the rows arrive, with the figures it measured writing that row's
// image (hits, encode_ms, write_ms). They queue behind the step's images without taking room.
//
// The writer's parallel work (the EXR and PNG of an image at once, their row loops) runs in its
// own arena of `output.writer_threads` threads, sized from the rank's budget (writer_thread_share
// in adaptor/step/thread_budget.hpp), at low priority: oneTBB's workers go to the renderer's arena
// first whenever a render step overlaps encoding. Its own arena, not the renderer's, so that a
// render step never picks up an encoding task while it waits for its own loops. With `mp4`, each
// scene's images are also appended to its movie, which finish() closes.
#pragma once

#include <tbb/task_arena.h>

#include <atomic>
#include <condition_variable>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <variant>
#include <vector>

#include "adaptor/config/config.hpp"
#include "adaptor/output/output_files.hpp"
#include "render/image/movie_writer.hpp"

namespace tetray {

// `<dir>/<scene>/<scene>_<first step, 6 digits>.mp4`: each run's movie starts at its first
// rendered step, so a run restarted into the same directory keeps the earlier run's movie.
std::string movie_path(const std::string& directory, const std::string& scene,
                       std::int64_t first_step);

class ImageWriter {
 public:
  // `budget`: the rank's threads (config.threads or default_thread_count()).
  ImageWriter(config::Output output, int budget);
  ~ImageWriter();  // finishes, then stops the thread
  ImageWriter(const ImageWriter&) = delete;
  ImageWriter& operator=(const ImageWriter&) = delete;

  // Returns once the queue has room for one more image (at once at depth 0), so that the caller
  // can time its wait apart from the rest of its hand-off. Only the writer thread takes from the
  // queue, so the room is still there at the caller's next submit.
  void wait_for_room();
  // Queues the job (or writes it, at depth 0), waiting for room first when there is none.
  void submit(ImageJob job);
  // The log rows of the images submitted since the last call, one per image in the same order
  // (or fewer: the images left over get no row). Never waits; an image that failed gets no row.
  void log_rows(std::vector<StepRecord> rows);
  // Returns when every submitted job is written.
  void drain();
  // Drains, then closes the movies (their errors become take_error's). Later jobs start new ones.
  void finish();

  bool has_error() const { return has_error_.load(std::memory_order_acquire); }
  // The first error since the last call (with a count of later ones); empty when none.
  std::string take_error();

 private:
  // An image to write, or the log rows of the images queued before it.
  using Task = std::variant<ImageJob, std::vector<StepRecord>>;

  void run();
  void perform(Task& task);
  void write(ImageJob& job);
  void append_log_rows(std::vector<StepRecord>& rows);
  std::string append_to_movie(const ImageJob& job);
  void keep_error(std::string error);

  config::Output output_;
  tbb::task_arena arena_;
  // Per scene; touched by whichever thread writes (one at a time: the writer thread, or the
  // caller at depth 0, and finish() only once the queue is drained).
  std::map<std::string, std::unique_ptr<render::MovieWriter>> movies_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Task> queue_;
  std::size_t queued_images_ = 0;  // the images in queue_, which writer_queue_depth bounds
  // The records of the images written since the last log rows, as written; none for an image
  // that failed. Touched by whichever thread writes, as movies_ is.
  std::deque<std::optional<StepRecord>> written_;
  bool busy_ = false;
  bool stopping_ = false;
  std::string error_;
  int later_errors_ = 0;
  std::atomic<bool> has_error_{false};
  std::thread thread_;  // last: started after every member it uses
};

}  // namespace tetray
