// MPI for a program's lifetime: the one place where MPI is started and finished (the yuxi
// program, the MPI tests, the benchmarks and the Python module all use it).
//
// Where yuxi is built with MPI, the first session starts it (MPI_Init) unless it is running
// already: a host that started it itself (mpi4py in the Python module) keeps it, and finishes
// it too. A session finishes MPI only if it started it. Built without MPI, a session does
// nothing and Comm::world() is a group of one.
#pragma once

#include "domain/comm.hpp"

namespace yuxi {

class MpiSession {
public:
  // `argc` and `argv` may be null (MPI_Init then gets none).
  MpiSession(int* argc = nullptr, char*** argv = nullptr);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

  // Whether this session started MPI (and will finish it).
  bool started_here() const { return started_here_; }
  // The whole job (a group of one without MPI).
  Comm world() const { return Comm::world(); }

private:
  bool started_here_ = false;
};

} // namespace yuxi
