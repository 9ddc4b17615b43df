#include "domain/comm.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#ifdef YUXI_HAVE_MPI
#include <mpi.h>
#endif

namespace yuxi {

#ifdef YUXI_HAVE_MPI
namespace {

// Open MPI's MPI_Comm is a pointer; the handle keeps it as an integer so that no MPI header
// leaks out of this file.
MPI_Comm to_mpi(std::intptr_t h) {
  return reinterpret_cast<MPI_Comm>(h);
}

bool mpi_running() {
  int initialized = 0, finalized = 0;
  MPI_Initialized(&initialized);
  MPI_Finalized(&finalized);
  return initialized && !finalized;
}

} // namespace

Comm Comm::from_handle(std::intptr_t handle) {
  int rank = 0, size = 1;
  MPI_Comm_rank(to_mpi(handle), &rank);
  MPI_Comm_size(to_mpi(handle), &size);
  return Comm(handle, rank, size);
}

Comm Comm::world() {
  return mpi_running() ? from_handle(reinterpret_cast<std::intptr_t>(MPI_COMM_WORLD))
                       : Comm(0, 0, 1);
}
Comm Comm::self() {
  return mpi_running() ? from_handle(reinterpret_cast<std::intptr_t>(MPI_COMM_SELF))
                       : Comm(0, 0, 1);
}

void Comm::sum(double* values, int n) const {
  if (size_ > 1) MPI_Allreduce(MPI_IN_PLACE, values, n, MPI_DOUBLE, MPI_SUM, to_mpi(handle_));
}

std::int64_t Comm::sum(std::int64_t v) const {
  if (size_ > 1) MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_INT64_T, MPI_SUM, to_mpi(handle_));
  return v;
}

double Comm::max(double v) const {
  if (size_ > 1) MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_DOUBLE, MPI_MAX, to_mpi(handle_));
  return v;
}

void Comm::max(double* values, int n) const {
  if (size_ > 1) MPI_Allreduce(MPI_IN_PLACE, values, n, MPI_DOUBLE, MPI_MAX, to_mpi(handle_));
}

bool Comm::any(bool v) const {
  int x = v ? 1 : 0;
  if (size_ > 1) MPI_Allreduce(MPI_IN_PLACE, &x, 1, MPI_INT, MPI_MAX, to_mpi(handle_));
  return x != 0;
}

void Comm::barrier() const {
  if (size_ > 1) MPI_Barrier(to_mpi(handle_));
}

std::uint64_t Comm::sum_below(std::uint64_t v) const {
  std::uint64_t below = 0;
  if (size_ > 1) MPI_Exscan(&v, &below, 1, MPI_UINT64_T, MPI_SUM, to_mpi(handle_));
  return rank_ == 0 ? 0 : below; // (MPI leaves rank 0's result undefined)
}

std::string Comm::send_receive(int dest, const std::string& out, int source, int tag) const {
  if (size_ == 1) return source < 0 ? std::string() : out;
  if (dest == rank_ && source == rank_) return out; // a periodic image of this rank's own
  const MPI_Comm c = to_mpi(handle_);
  dest = dest < 0 ? MPI_PROC_NULL : dest; // no neighbour: nothing is sent or received
  source = source < 0 ? MPI_PROC_NULL : source;
  std::uint64_t n_out = dest == MPI_PROC_NULL ? 0 : out.size(), n_in = 0;
  MPI_Sendrecv(&n_out, 1, MPI_UINT64_T, dest, tag, &n_in, 1, MPI_UINT64_T, source, tag, c,
               MPI_STATUS_IGNORE);
  std::string in(n_in, '\0');
  MPI_Sendrecv(out.data(), static_cast<int>(n_out), MPI_BYTE, dest, tag + 1, in.data(),
               static_cast<int>(n_in), MPI_BYTE, source, tag + 1, c, MPI_STATUS_IGNORE);
  return in;
}

void Comm::send_receive(int dest, const std::string& out, int source, std::string& in,
                        std::size_t in_bytes, int tag) const {
  if (size_ == 1) {
    in = source < 0 ? std::string() : out;
    return;
  }
  const MPI_Comm c = to_mpi(handle_);
  dest = dest < 0 ? MPI_PROC_NULL : dest;
  source = source < 0 ? MPI_PROC_NULL : source;
  in.resize(source == MPI_PROC_NULL ? 0 : in_bytes);
  MPI_Sendrecv(out.data(), dest == MPI_PROC_NULL ? 0 : static_cast<int>(out.size()), MPI_BYTE, dest,
               tag, in.data(), static_cast<int>(in.size()), MPI_BYTE, source, tag, c,
               MPI_STATUS_IGNORE);
}

namespace {
// An Exchange keeps its MPI_Request values as integers (no MPI header leaks out of this file).
static_assert(sizeof(MPI_Request) <= sizeof(std::intptr_t));
std::intptr_t stored_request(MPI_Request request) {
  std::intptr_t stored = 0;
  std::memcpy(&stored, &request, sizeof(MPI_Request));
  return stored;
}

std::vector<MPI_Request> requests_of(const std::vector<std::intptr_t>& stored) {
  std::vector<MPI_Request> requests(stored.size());
  for (std::size_t k = 0; k < stored.size(); ++k)
    std::memcpy(&requests[k], &stored[k], sizeof(MPI_Request));
  return requests;
}

void wait_for(std::vector<std::intptr_t>& stored) {
  if (stored.empty() || !mpi_running()) return;
  std::vector<MPI_Request> requests = requests_of(stored);
  MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
  stored.clear();
}

// The bytes of each piece of a message of `bytes`: exchange_piece_bytes, or larger where that
// would make more than max_exchange_pieces pieces.
std::size_t piece_bytes(std::size_t bytes) {
  return std::max(Comm::exchange_piece_bytes,
                  (bytes + Comm::max_exchange_pieces - 1) / Comm::max_exchange_pieces);
}
} // namespace

Comm::Exchange Comm::start_send_receive(int dest, const std::string& out, int source,
                                        std::string& in, std::size_t in_bytes, int tag) const {
  Exchange e;
  if (size_ == 1 || (dest == rank_ && source == rank_)) {
    in = source < 0 ? std::string() : out;
    return e;
  }
  const MPI_Comm c = to_mpi(handle_);
  in.resize(source < 0 ? 0 : in_bytes);
  // Each piece of a message of `bytes`, at least one (an empty message still arrives); no
  // neighbour (peer < 0): nothing travels.
  const auto each_piece = [](std::size_t bytes, int peer, auto post) {
    if (peer < 0) return;
    const std::size_t piece = piece_bytes(bytes);
    std::size_t at = 0;
    do {
      post(at, static_cast<int>(std::min(piece, bytes - at)));
      at += piece;
    } while (at < bytes);
  };
  // (The pieces of one message match their receives in order: MPI keeps the order of the
  // messages between two ranks with the same tag.)
  each_piece(in.size(), source, [&](std::size_t at, int count) {
    MPI_Request request;
    MPI_Irecv(in.data() + at, count, MPI_BYTE, source, tag, c, &request);
    e.receives.push_back(stored_request(request));
  });
  each_piece(out.size(), dest, [&](std::size_t at, int count) {
    MPI_Request request;
    MPI_Isend(out.data() + at, count, MPI_BYTE, dest, tag, c, &request);
    e.sends.push_back(stored_request(request));
  });
  return e;
}

void Comm::wait_receive(Exchange& e) const {
  wait_for(e.receives);
}

void Comm::wait_send(Exchange& e) const {
  wait_for(e.sends);
}

void Comm::cancel_receive(Exchange& e) const {
  if (!mpi_running()) return;
  for (MPI_Request r : requests_of(e.receives)) MPI_Cancel(&r); // (a request is a handle)
  wait_for(e.receives);
}

std::vector<std::string> Comm::gather(std::string mine) const {
  if (size_ == 1) {
    std::vector<std::string> out;
    out.push_back(std::move(mine));
    return out;
  }
  const MPI_Comm c = to_mpi(handle_);
  const int n = static_cast<int>(mine.size());
  std::vector<int> sizes(static_cast<std::size_t>(size_)), offsets(static_cast<std::size_t>(size_));
  MPI_Gather(&n, 1, MPI_INT, sizes.data(), 1, MPI_INT, 0, c);
  std::string all;
  if (root()) {
    int total = 0;
    for (int r = 0; r < size_; ++r)
      offsets[static_cast<std::size_t>(r)] = total, total += sizes[static_cast<std::size_t>(r)];
    all.resize(static_cast<std::size_t>(total));
  }
  MPI_Gatherv(mine.data(), n, MPI_BYTE, all.data(), sizes.data(), offsets.data(), MPI_BYTE, 0, c);
  std::vector<std::string> out;
  if (root())
    for (int r = 0; r < size_; ++r)
      out.push_back(all.substr(static_cast<std::size_t>(offsets[static_cast<std::size_t>(r)]),
                               static_cast<std::size_t>(sizes[static_cast<std::size_t>(r)])));
  return out;
}

std::vector<std::string> Comm::all_gather(const std::string& mine) const {
  if (size_ == 1) return {mine};
  auto parts = gather(mine);
  std::string packed;
  if (root())
    for (const auto& p : parts) {
      const std::uint64_t n = p.size();
      packed.append(reinterpret_cast<const char*>(&n), sizeof n);
      packed += p;
    }
  packed = broadcast(packed);
  std::vector<std::string> out;
  for (std::size_t at = 0; at < packed.size();) {
    std::uint64_t n = 0;
    std::memcpy(&n, packed.data() + at, sizeof n);
    out.push_back(packed.substr(at + sizeof n, n));
    at += sizeof n + n;
  }
  return out;
}

std::string Comm::broadcast(const std::string& from_root) const {
  if (size_ == 1) return from_root;
  const MPI_Comm c = to_mpi(handle_);
  std::uint64_t n = from_root.size();
  MPI_Bcast(&n, 1, MPI_UINT64_T, 0, c);
  std::string out = root() ? from_root : std::string(n, '\0');
  MPI_Bcast(out.data(), static_cast<int>(n), MPI_BYTE, 0, c);
  return out;
}

std::string Comm::first_error(const std::string& mine) const {
  if (size_ == 1) return mine;
  int first = mine.empty() ? size_ : rank_;
  MPI_Allreduce(MPI_IN_PLACE, &first, 1, MPI_INT, MPI_MIN, to_mpi(handle_));
  if (first == size_) return {};
  // the message travels from the first failing rank to all
  std::uint64_t n = mine.size();
  MPI_Bcast(&n, 1, MPI_UINT64_T, first, to_mpi(handle_));
  std::string out = rank_ == first ? mine : std::string(n, '\0');
  MPI_Bcast(out.data(), static_cast<int>(n), MPI_BYTE, first, to_mpi(handle_));
  return out;
}

#else // a group of one

Comm Comm::from_handle(std::intptr_t) {
  return Comm(0, 0, 1);
}
Comm Comm::world() {
  return Comm(0, 0, 1);
}
Comm Comm::self() {
  return Comm(0, 0, 1);
}
void Comm::sum(double*, int) const {}
std::int64_t Comm::sum(std::int64_t v) const {
  return v;
}
double Comm::max(double v) const {
  return v;
}
void Comm::max(double*, int) const {}
bool Comm::any(bool v) const {
  return v;
}
void Comm::barrier() const {}
std::uint64_t Comm::sum_below(std::uint64_t) const {
  return 0;
}
std::string Comm::send_receive(int, const std::string& out, int source, int) const {
  return source < 0 ? std::string() : out;
}
void Comm::send_receive(int, const std::string& out, int source, std::string& in, std::size_t,
                        int) const {
  in = source < 0 ? std::string() : out;
}
Comm::Exchange Comm::start_send_receive(int, const std::string& out, int source, std::string& in,
                                        std::size_t, int) const {
  in = source < 0 ? std::string() : out;
  return {};
}
void Comm::wait_receive(Exchange&) const {}
void Comm::wait_send(Exchange&) const {}
void Comm::cancel_receive(Exchange&) const {}
std::vector<std::string> Comm::gather(std::string mine) const {
  std::vector<std::string> out;
  out.push_back(std::move(mine));
  return out;
}
std::vector<std::string> Comm::all_gather(const std::string& mine) const {
  return {mine};
}
std::string Comm::broadcast(const std::string& from_root) const {
  return from_root;
}
std::string Comm::first_error(const std::string& mine) const {
  return mine;
}

#endif

double Comm::sum(double v) const {
  sum(&v, 1);
  return v;
}

double Comm::max_over_mean(double v) const {
  const double mean = sum(v) / size_;
  return mean > 0 ? max(v) / mean : 1.0;
}

} // namespace yuxi
