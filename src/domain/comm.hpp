// The process group a simulation runs on: with SharedFile (its files), the one place where MPI
// calls are made. Built
// without MPI (or run on one rank) it is a group of one, and every operation is local.
//
// Everything that crosses ranks is bytes: particles, ghost fields and contact histories are
// packed by their owners (the domain layer never depends on contact models).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace yuxi {

class Comm {
public:
  // The whole job (MPI_COMM_WORLD), or a group of one if MPI is not initialised or not built.
  static Comm world();
  // A group of one (MPI_COMM_SELF): a serial run inside an MPI job.
  static Comm self();

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool root() const { return rank_ == 0; }

  double sum(double v) const;
  void sum(double* values, int n) const;
  std::int64_t sum(std::int64_t v) const;
  double max(double v) const;
  void max(double* values, int n) const; // element-wise, in place
  bool any(bool v) const;
  // Returns once every rank has called it.
  void barrier() const;
  // The sum of v over the ranks below this one (0 on rank 0): where this rank's part starts
  // when the ranks' parts follow each other in rank order.
  std::uint64_t sum_below(std::uint64_t v) const;
  // Largest v over the ranks divided by the mean (1 if the mean is 0): a load imbalance.
  double max_over_mean(double v) const;
  // Sends `out` to `dest` and receives from `source` (either may be this rank).
  std::string send_receive(int dest, const std::string& out, int source, int tag) const;
  // The same when both sides know the sizes: receives exactly `in_bytes` into `in` (reused
  // storage), in one message instead of two.
  void send_receive(int dest, const std::string& out, int source, std::string& in,
                    std::size_t in_bytes, int tag) const;
  // A send-receive under way (from start_send_receive() until wait_send() and wait_receive()):
  // its outgoing string may not be touched before the one, its incoming one before the other.
  struct Exchange {
    std::vector<std::intptr_t> sends, receives; // MPI_Request values, one per piece
  };
  // The second send_receive() split up, so that the caller computes while the bytes travel:
  // start posts both sides and returns at once; wait_receive() returns once `in` holds the
  // bytes, wait_send() once `out` may be touched again (the receiver has taken them: a rank
  // need not wait for the other to reach its wait_receive() until it reuses `out`).
  // The bytes travel in pieces, each its own message. MPI moves a message only inside MPI
  // calls, and a large one needs both ranks there: Open MPI's shared-memory transport delivers
  // a message over 4 kB only once the receiver has answered the sender, so the ghosts' forces
  // waited for the sender's next MPI call, after all its pairs and its integration. A message
  // of at most 4 kB is delivered whole when it is sent (eagerly), and so are these pieces: the
  // bytes are all at the receiver when it reaches wait_receive(), though the sender has been
  // computing since. (Measured on the paper-size basin on 2 ranks: the receiving rank's wait
  // fell from 0.6 - 3.4 ms a step to 0.1 ms.) Pieces are larger than exchange_piece_bytes only
  // where there would be more than max_exchange_pieces. Both sides of a message must use this
  // call: the other send_receive() sends one message.
  static constexpr std::size_t exchange_piece_bytes = 4000; // (under 4 kB with MPI's header)
  static constexpr std::size_t max_exchange_pieces = 64;
  Exchange start_send_receive(int dest, const std::string& out, int source, std::string& in,
                              std::size_t in_bytes, int tag) const;
  void wait_receive(Exchange& exchange) const;
  void wait_send(Exchange& exchange) const;
  // Withdraws a receive not waited for (a step cut short by an error): `in` is free again.
  void cancel_receive(Exchange& exchange) const;
  // Rank 0 gets every rank's bytes, in rank order; the others get nothing.
  // (Taken by value: on one rank the bytes move through without a copy.)
  std::vector<std::string> gather(std::string mine) const;
  // Every rank gets every rank's bytes.
  std::vector<std::string> all_gather(const std::string& mine) const;
  // Rank 0's bytes on every rank.
  std::string broadcast(const std::string& from_root) const;
  // The message of the lowest rank whose message is not empty ("" if none): lets every rank
  // stop together with one diagnosis.
  std::string first_error(const std::string& mine) const;

private:
  friend class SharedFile;                       // opens its files on this group
  friend class CollectiveGuard;                  // duplicates this group's communicator
  static Comm from_handle(std::intptr_t handle); // reads rank and size from MPI
  Comm(std::intptr_t handle, int rank, int size) : handle_(handle), rank_(rank), size_(size) {}
  std::intptr_t handle_; // MPI_Comm stored as an integer (0: no MPI)
  int rank_;
  int size_;
};

} // namespace yuxi
