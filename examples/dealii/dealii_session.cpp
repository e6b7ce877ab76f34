#include "dealii_session.hpp"

#include <deal.II/base/mpi.h>

struct DealiiSession::Runtime {
  dealii::Utilities::MPI::MPI_InitFinalize mpi;
};

DealiiSession::DealiiSession(int& argc, char**& argv)
    : runtime_(new Runtime{dealii::Utilities::MPI::MPI_InitFinalize(argc, argv, 1)}) {}

DealiiSession::~DealiiSession() = default;
