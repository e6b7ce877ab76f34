// MPI as deal.II starts it (Utilities::MPI::MPI_InitFinalize: MPI, p4est, and the Trilinos and
// PETSc pieces deal.II was built with), behind a header without deal.II so that main.cpp need not
// compile deal.II's headers.
#pragma once

#include <memory>

class DealiiSession {
 public:
  DealiiSession(int& argc, char**& argv);  // one thread per rank: tetray has its own threads
  ~DealiiSession();
  DealiiSession(const DealiiSession&) = delete;
  DealiiSession& operator=(const DealiiSession&) = delete;

 private:
  struct Runtime;
  std::unique_ptr<Runtime> runtime_;
};
