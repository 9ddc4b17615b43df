// What the exchanges of one time step cost with nothing else to do: two ranks swap the bytes
// of GHOSTS ghosts' fields (Halo::forward_bytes_per_ghost each), then of their forces
// (Halo::reverse_bytes_per_ghost each), with MPI_Sendrecv, and reduce three doubles (the step's
// collective, Simulation::step()), again and again. The time of one such round is a floor under
// a 2-rank run's "comm" share: the transport alone, with no packing, no waiting for a slower
// rank and no cache misses on the particles. bench/scaling.sh runs it with the ghost count a
// 2-rank run reports ("halo: ..." in its log).
// usage: mpirun -np 2 build/release/bench/exchange_cost GHOSTS [ROUNDS]
#include "domain/halo.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <mpi.h>
#include <string>
#include <vector>

namespace {

// Seconds per round of `round()`, the fastest of five batches of `rounds` (other jobs on the
// machine only ever slow a batch down).
template <class Round> double seconds_per_round(int rounds, Round&& round) {
  double best = 1e30;
  for (int batch = 0; batch < 5; ++batch) {
    MPI_Barrier(MPI_COMM_WORLD);
    const double start = MPI_Wtime();
    for (int k = 0; k < rounds; ++k) round();
    double elapsed = (MPI_Wtime() - start) / rounds;
    MPI_Allreduce(MPI_IN_PLACE, &elapsed, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    best = std::min(best, elapsed);
  }
  return best;
}

} // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0, size = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  const long ghosts = argc > 1 ? std::atol(argv[1]) : -1;
  const int rounds = argc > 2 ? std::atoi(argv[2]) : 2000;
  if (size != 2 || ghosts < 0 || rounds <= 0) {
    if (rank == 0) std::fprintf(stderr, "usage: mpirun -np 2 exchange_cost GHOSTS [ROUNDS]\n");
    MPI_Finalize();
    return 2;
  }
  const int other = 1 - rank;
  const auto n = static_cast<std::size_t>(ghosts);
  std::string fields_out(n * yuxi::Halo::forward_bytes_per_ghost, 'x'), fields_in(fields_out);
  std::string forces_out(n * yuxi::Halo::reverse_bytes_per_ghost, 'f'), forces_in(forces_out);
  const auto swap = [&](std::string& out, std::string& in) {
    MPI_Sendrecv(out.data(), static_cast<int>(out.size()), MPI_BYTE, other, 1, in.data(),
                 static_cast<int>(in.size()), MPI_BYTE, other, 1, MPI_COMM_WORLD,
                 MPI_STATUS_IGNORE);
  };
  double flags[3] = {0, 0, 0};
  const auto reduce = [&] {
    MPI_Allreduce(MPI_IN_PLACE, flags, 3, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  };
  const double forward = seconds_per_round(rounds, [&] { swap(fields_out, fields_in); });
  const double reverse = seconds_per_round(rounds, [&] { swap(forces_out, forces_in); });
  const double collective = seconds_per_round(rounds, reduce);
  const double step = seconds_per_round(rounds, [&] {
    reduce();
    swap(fields_out, fields_in);
    swap(forces_out, forces_in);
  });
  if (rank == 0)
    std::printf("%ld ghosts: fields %.0f B in %.2f us, forces %.0f B in %.2f us, collective %.2f "
                "us; a step's exchanges %.2f us\n",
                ghosts, static_cast<double>(fields_out.size()), forward * 1e6,
                static_cast<double>(forces_out.size()), reverse * 1e6, collective * 1e6,
                step * 1e6);
  MPI_Finalize();
  return 0;
}
