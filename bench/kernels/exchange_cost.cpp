// What the exchanges of one time step cost with nothing else to do: two ranks swap the bytes
// of GHOSTS ghosts' fields (Halo::forward_bytes_per_ghost each), then of their forces
// (Halo::reverse_bytes_per_ghost each), with MPI_Sendrecv (Comm::send_receive), and reduce three
// doubles (the step's collective, Simulation::step()), again and again. The time of one such round
// is a floor under a 2-rank run's "comm" share: the transport alone, with no packing, no waiting
// for a slower rank and no cache misses on the particles. bench/scaling.sh runs it with the ghost
// count a 2-rank run reports ("halo: ..." in its log). usage: mpirun -np 2
// build/release/bench/exchange_cost GHOSTS [ROUNDS]
#include "domain/comm.hpp"
#include "domain/halo.hpp"
#include "domain/mpi_session.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace {

// Seconds per round of `round()`, the slower rank's, the fastest of five batches of `rounds`
// (other jobs on the machine only ever slow a batch down).
template <class Round> double seconds_per_round(const yuxi::Comm& comm, int rounds, Round&& round) {
  double best = 1e30;
  for (int batch = 0; batch < 5; ++batch) {
    comm.barrier();
    const auto start = std::chrono::steady_clock::now();
    for (int k = 0; k < rounds; ++k) round();
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / rounds;
    best = std::min(best, comm.max(elapsed));
  }
  return best;
}

} // namespace

int main(int argc, char** argv) {
  const yuxi::MpiSession mpi(&argc, &argv);
  int status = 0;
  {
    // The engine's own calls (Comm): the sized send-receive of Halo::forward() and the
    // reduction of Simulation::step().
    const yuxi::Comm comm = yuxi::Comm::world();
    const long ghosts = argc > 1 ? std::atol(argv[1]) : -1;
    const int rounds = argc > 2 ? std::atoi(argv[2]) : 2000;
    if (comm.size() != 2 || ghosts < 0 || rounds <= 0) {
      if (comm.root()) std::fprintf(stderr, "usage: mpirun -np 2 exchange_cost GHOSTS [ROUNDS]\n");
      status = 2;
    } else {
      const int other = 1 - comm.rank();
      const auto n = static_cast<std::size_t>(ghosts);
      const std::string fields_out(n * yuxi::Halo::forward_bytes_per_ghost, 'x');
      const std::string forces_out(n * yuxi::Halo::reverse_bytes_per_ghost, 'f');
      std::string in;
      const auto swap = [&](const std::string& out) {
        comm.send_receive(other, out, other, in, out.size(), 1);
      };
      double flags[3] = {0, 0, 0};
      const auto reduce = [&] { comm.max(flags, 3); };
      const double forward = seconds_per_round(comm, rounds, [&] { swap(fields_out); });
      const double reverse = seconds_per_round(comm, rounds, [&] { swap(forces_out); });
      const double collective = seconds_per_round(comm, rounds, reduce);
      const double step = seconds_per_round(comm, rounds, [&] {
        reduce();
        swap(fields_out);
        swap(forces_out);
      });
      if (comm.root())
        std::printf("%ld ghosts: fields %.0f B in %.2f us, forces %.0f B in %.2f us, collective "
                    "%.2f us; a step's exchanges %.2f us\n",
                    ghosts, static_cast<double>(fields_out.size()), forward * 1e6,
                    static_cast<double>(forces_out.size()), reverse * 1e6, collective * 1e6,
                    step * 1e6);
    }
  }
  return status;
}
