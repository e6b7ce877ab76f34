// The few collective operations the solver needs, behind an interface so the physics runs and is
// tested on one process without MPI (SerialComm) and across ranks with it (MpiComm).
#pragma once

#include <mpi.h>

#include <span>
#include <vector>

namespace minisolver {

class Comm {
 public:
  virtual ~Comm() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  virtual double sum(double local) const = 0;
  virtual double max(double local) const = 0;
  // Sends send[i] to peers[i] and receives recv[i] (already sized) from peers[i].
  virtual void exchange(std::span<const int> peers, const std::vector<std::vector<double>>& send,
                        std::vector<std::vector<double>>& recv) const = 0;
};

class SerialComm final : public Comm {
 public:
  int rank() const override { return 0; }
  int size() const override { return 1; }
  double sum(double local) const override { return local; }
  double max(double local) const override { return local; }
  void exchange(std::span<const int>, const std::vector<std::vector<double>>&,
                std::vector<std::vector<double>>&) const override {}
};

class MpiComm final : public Comm {
 public:
  explicit MpiComm(MPI_Comm comm) : comm_(comm) {}
  int rank() const override;
  int size() const override;
  double sum(double local) const override;
  double max(double local) const override;
  void exchange(std::span<const int> peers, const std::vector<std::vector<double>>& send,
                std::vector<std::vector<double>>& recv) const override;
  MPI_Comm raw() const { return comm_; }

 private:
  MPI_Comm comm_;
};

}  // namespace minisolver
