// For tests run under mpirun: this process's rank and the world's size, and a directory made by
// rank 0, known to every rank, removed by rank 0 once all are done.
#pragma once

#include <mpi.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>

namespace tetray::testing {

inline int rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

inline int world_size() {
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  return size;
}

class SharedDir {
 public:
  explicit SharedDir(const std::string& name) {
    char path[256] = {};
    if (rank() == 0) {
      const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                        ("tetray_mpi_" + std::to_string(::getpid()) + name);
      std::filesystem::remove_all(dir);
      std::filesystem::create_directories(dir);
      std::snprintf(path, sizeof path, "%s", dir.c_str());
    }
    MPI_Bcast(path, sizeof path, MPI_CHAR, 0, MPI_COMM_WORLD);
    path_ = path;
  }
  ~SharedDir() {
    MPI_Barrier(MPI_COMM_WORLD);
    if (rank() == 0) std::filesystem::remove_all(path_);
  }
  SharedDir(const SharedDir&) = delete;
  SharedDir& operator=(const SharedDir&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace tetray::testing
