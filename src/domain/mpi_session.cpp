#include "domain/mpi_session.hpp"

#include <cstdlib>

#ifdef YUXI_HAVE_MPI
#include <mpi.h>
#endif

namespace yuxi {

MpiSession::MpiSession([[maybe_unused]] int* argc, [[maybe_unused]] char*** argv) {
#ifdef YUXI_HAVE_MPI
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (initialized) return; // (started by the host: it finishes it)
  // Open MPI moves a large message between ranks of one machine with a single copy by the
  // kernel (CMA, process_vm_readv) by default. yuxi's messages are halos of a few hundred kB at
  // most, every step, and for them the system call costs more than it saves: on 2-core
  // machines the copy through shared-memory buffers halves the communication time of the chute
  // on 2 ranks (16% -> 8-10% of the step) and of basin-small (66% -> 45%). A value the user set
  // (environment or mpirun --mca) wins.
  setenv("OMPI_MCA_btl_vader_single_copy_mechanism", "none", 0);
  MPI_Init(argc, argv);
  started_here_ = true;
#endif
}

MpiSession::~MpiSession() {
#ifdef YUXI_HAVE_MPI
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (started_here_ && !finalized) MPI_Finalize();
#endif
}

} // namespace yuxi
