// A file that the ranks of a group write together, each rank its own bytes at offsets it
// computes, so that no rank gathers the others' data: for 10^6 particles and more, gathering
// every frame and checkpoint on rank 0 costs that rank the whole system's memory and leaves the
// others waiting while it writes. Built on MPI-IO (which also places the ranks' writes into one
// file on a parallel file system shared by several machines); on a group of one, on plain
// POSIX calls.
//
// A failed call does not throw where it fails: the other ranks would wait forever in the next
// collective call. The first failure is kept, later writes are skipped, and close() throws on
// every rank with the message of the lowest failing rank.
#pragma once

#include "domain/comm.hpp"

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace yuxi {

class SharedFile {
public:
  enum class Mode {
    truncate, // start empty (created if missing)
    append    // keep what the file holds (created if missing); see size_at_open()
  };
  // Collective over `comm`: every rank opens the same path.
  SharedFile(const Comm& comm, std::filesystem::path path, Mode mode);
  // A file not closed (an exception between opening and close()) is closed on a group of one;
  // under MPI it is left to MPI_Finalize, since closing is collective and the other ranks may
  // not be closing it.
  ~SharedFile();
  SharedFile(const SharedFile&) = delete;
  SharedFile& operator=(const SharedFile&) = delete;

  // The file's size when it was opened, the same on every rank (0 when truncated): where
  // appended bytes start.
  std::uint64_t size_at_open() const { return size_at_open_; }
  // Writes `bytes` at byte `offset` (this rank alone; ranks must not overlap).
  void write_at(std::uint64_t offset, std::string_view bytes);
  // Collective: writes every rank's `bytes` one after the other in rank order from `offset`,
  // and returns where the last rank's end (the same on every rank).
  std::uint64_t write_in_rank_order(std::uint64_t offset, std::string_view bytes);
  // Collective: flushes the file to the disk if `durable`, closes it, and throws
  // std::runtime_error on every rank if any rank failed since it was opened.
  void close(bool durable);

private:
  void fail(const std::string& what);
  bool uses_mpi() const;

  Comm comm_;
  std::filesystem::path path_;
  std::intptr_t mpi_file_ = 0; // MPI_File as an integer (MPI-IO), or
  int fd_ = -1;                // a POSIX file descriptor (a group of one)
  bool open_ = false;
  std::uint64_t size_at_open_ = 0;
  std::string error_; // the first failure on this rank
};

} // namespace yuxi
