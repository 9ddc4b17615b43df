#include "domain/collective_guard.hpp"

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fmt/format.h>
#include <thread>
#include <vector>

#ifdef YUXI_HAVE_MPI
#include <mpi.h>
#endif

namespace yuxi {
namespace {

// FNV-1a, 32 bits: exact as a double, so that one reduction of (h, -h) compares the ranks'.
double call_hash(std::string_view call) {
  std::uint32_t h = 2166136261u;
  for (const char c : call) {
    h ^= static_cast<unsigned char>(c);
    h *= 16777619u;
  }
  return static_cast<double>(h);
}

} // namespace

double CollectiveGuard::default_timeout() {
  if (const char* s = std::getenv("YUXI_COLLECTIVE_TIMEOUT")) {
    char* end = nullptr;
    const double t = std::strtod(s, &end);
    if (end != s && t > 0.0 && std::isfinite(t)) return t;
  }
  return 600.0;
}

void CollectiveGuard::set_timeout(double seconds) {
  if (!(seconds > 0.0) || !std::isfinite(seconds))
    throw std::invalid_argument(
        fmt::format("collective timeout: must be a positive number of seconds (got {})", seconds));
  timeout_ = seconds;
}

#ifdef YUXI_HAVE_MPI

CollectiveGuard::CollectiveGuard(const Comm& comm, double timeout_s)
    : rank_(comm.rank()), size_(comm.size()), timeout_(timeout_s),
      pending_(std::make_unique<double[]>(2)) {
  set_timeout(timeout_s);
  if (size_ == 1) return;
  // (Comm keeps its MPI_Comm as an integer; so does this guard)
  MPI_Comm dup = MPI_COMM_NULL;
  MPI_Comm_dup(reinterpret_cast<MPI_Comm>(comm.handle_), &dup);
  handle_ = reinterpret_cast<std::intptr_t>(dup);
}

CollectiveGuard::~CollectiveGuard() {
  if (!out_of_step_.empty()) {
    (void)pending_.release(); // MPI may still write it
    return;
  }
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (handle_ != 0 && !finalized) {
    MPI_Comm dup = reinterpret_cast<MPI_Comm>(handle_);
    MPI_Comm_free(&dup);
  }
}

void CollectiveGuard::enter(std::string_view call) {
  if (size_ == 1) return;
  if (!out_of_step_.empty())
    throw CollectiveMismatch(
        fmt::format("{}: the ranks are out of step since {} timed out on rank {}; end the job",
                    call, out_of_step_, rank_));
  const MPI_Comm comm = reinterpret_cast<MPI_Comm>(handle_);
  double* v = pending_.get();
  v[0] = call_hash(call);
  v[1] = -v[0];
  MPI_Request request = MPI_REQUEST_NULL;
  MPI_Iallreduce(MPI_IN_PLACE, v, 2, MPI_DOUBLE, MPI_MAX, comm, &request);
  const auto start = std::chrono::steady_clock::now();
  for (int polls = 0;; ++polls) {
    int done = 0;
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) break;
    const std::chrono::duration<double> waited = std::chrono::steady_clock::now() - start;
    if (waited.count() > timeout_) {
      out_of_step_ = std::string(call);
      throw CollectiveMismatch(fmt::format(
          "{} is collective: every rank must call it, in the same order, but rank {} waited {:.0f} "
          "s and not every rank did (a call under `if rank == 0:`?). The ranks are out of step; "
          "end the job",
          call, rank_, waited.count()));
    }
    // (at first at once, then without spinning a core)
    if (polls > 1000) std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  if (v[0] == -v[1]) return;
  // Every rank is here, in different calls: each learns every rank's.
  const std::string mine(call);
  int n = static_cast<int>(mine.size());
  std::vector<int> sizes(static_cast<std::size_t>(size_));
  MPI_Allgather(&n, 1, MPI_INT, sizes.data(), 1, MPI_INT, comm);
  std::vector<int> offsets(static_cast<std::size_t>(size_), 0);
  for (std::size_t r = 1; r < sizes.size(); ++r) offsets[r] = offsets[r - 1] + sizes[r - 1];
  std::string all(static_cast<std::size_t>(offsets.back() + sizes.back()), '\0');
  MPI_Allgatherv(mine.data(), n, MPI_CHAR, all.data(), sizes.data(), offsets.data(), MPI_CHAR,
                 comm);
  std::string calls;
  for (std::size_t r = 0; r < sizes.size(); ++r)
    calls += fmt::format(
        "{}rank {}: {}", r == 0 ? "" : ", ", r,
        all.substr(static_cast<std::size_t>(offsets[r]), static_cast<std::size_t>(sizes[r])));
  throw CollectiveMismatch(fmt::format(
      "{} is collective: every rank must make the same collective calls in the same order, but "
      "the ranks met in different ones ({})",
      call, calls));
}

#else // a group of one

CollectiveGuard::CollectiveGuard(const Comm&, double timeout_s) : timeout_(timeout_s) {
  set_timeout(timeout_s);
}
CollectiveGuard::~CollectiveGuard() = default;
void CollectiveGuard::enter(std::string_view) {}

#endif

} // namespace yuxi
