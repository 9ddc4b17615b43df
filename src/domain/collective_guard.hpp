// A check that the ranks make the same collective call, for a layer whose calls a user writes
// (Python): a call that only some ranks make (under `if rank == 0:`), or ranks that make
// different ones, would otherwise wait forever inside MPI. Before each such call every rank
// says which call it makes, over a communicator of the guard's own (its messages never meet
// the simulation's), and waits at most a timeout for the others.
#pragma once

#include "domain/comm.hpp"

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>

namespace yuxi {

// A collective call that not every rank made: what() names the call and, where the ranks met
// in different calls, each rank's.
class CollectiveMismatch : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

class CollectiveGuard {
public:
  // Collective over `comm` (which it duplicates). `timeout_s`: how long a rank waits for the
  // others at a call before it gives up [s].
  explicit CollectiveGuard(const Comm& comm, double timeout_s = default_timeout());
  CollectiveGuard(const CollectiveGuard&) = delete;
  CollectiveGuard& operator=(const CollectiveGuard&) = delete;
  ~CollectiveGuard();

  // Returns once every rank has entered a call named `call`. Throws CollectiveMismatch on every
  // rank where the ranks entered different calls (naming each rank's), and on this rank where
  // the others have not all entered one within the timeout: the ranks are then out of step,
  // and every later call on this guard throws at once. On one rank it returns at once.
  void enter(std::string_view call);

  double timeout() const { return timeout_; }
  void set_timeout(double seconds);
  // $YUXI_COLLECTIVE_TIMEOUT seconds where set, else 600.
  static double default_timeout();

private:
  std::intptr_t handle_ = 0; // the duplicated MPI_Comm (0: one rank, or no MPI)
  int rank_ = 0, size_ = 1;
  double timeout_;
  // The buffer of the agreement under way; after a timeout it stays with MPI, which may still
  // write it, and is never freed.
  std::unique_ptr<double[]> pending_;
  std::string out_of_step_; // the call that timed out ("" while the ranks are in step)
};

} // namespace yuxi
