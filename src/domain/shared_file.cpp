#include "domain/shared_file.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <fmt/format.h>
#include <stdexcept>
#include <sys/stat.h>
#include <unistd.h>

#ifdef YUXI_HAVE_MPI
#include <mpi.h>
#endif

namespace yuxi {
namespace {

// Bytes per write call: MPI counts are ints, and POSIX writes may stop short anyway.
constexpr std::size_t chunk_bytes = std::size_t{1} << 30;

#ifdef YUXI_HAVE_MPI
MPI_File to_file(std::intptr_t h) {
  return reinterpret_cast<MPI_File>(h);
}

std::string mpi_message(int code) {
  char text[MPI_MAX_ERROR_STRING];
  int length = 0;
  MPI_Error_string(code, text, &length);
  return std::string(text, static_cast<std::size_t>(length));
}
#endif

} // namespace

bool SharedFile::uses_mpi() const {
#ifdef YUXI_HAVE_MPI
  return comm_.size() > 1 && comm_.handle_ != 0;
#else
  return false;
#endif
}

void SharedFile::fail(const std::string& what) {
  if (error_.empty()) error_ = fmt::format("{}: {}", path_.string(), what);
}

SharedFile::SharedFile(const Comm& comm, std::filesystem::path path, Mode mode)
    : comm_(comm), path_(std::move(path)) {
  if (!uses_mpi()) {
    fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | (mode == Mode::truncate ? O_TRUNC : 0), 0644);
    if (fd_ < 0) {
      fail(fmt::format("cannot open for writing: {}", std::strerror(errno)));
      return;
    }
    open_ = true;
    struct stat st {};
    if (::fstat(fd_, &st) == 0) size_at_open_ = static_cast<std::uint64_t>(st.st_size);
    return;
  }
#ifdef YUXI_HAVE_MPI
  MPI_File file = MPI_FILE_NULL;
  const int code = MPI_File_open(reinterpret_cast<MPI_Comm>(comm_.handle_), path_.c_str(),
                                 MPI_MODE_WRONLY | MPI_MODE_CREATE, MPI_INFO_NULL, &file);
  // Opening is collective and fails on every rank or none (MPI-IO agrees on it).
  if (code != MPI_SUCCESS) {
    fail(fmt::format("cannot open for writing: {}", mpi_message(code)));
    return;
  }
  mpi_file_ = reinterpret_cast<std::intptr_t>(file);
  open_ = true;
  if (mode == Mode::truncate) {
    if (const int c = MPI_File_set_size(file, 0); c != MPI_SUCCESS)
      fail(fmt::format("cannot truncate: {}", mpi_message(c)));
  } else {
    // Rank 0's view of the size, on every rank: a rank that had just shortened the file before
    // this collective open is seen the same by all.
    MPI_Offset size = 0;
    if (comm_.root()) MPI_File_get_size(file, &size);
    MPI_Bcast(&size, 1, MPI_OFFSET, 0, reinterpret_cast<MPI_Comm>(comm_.handle_));
    size_at_open_ = static_cast<std::uint64_t>(size);
  }
#endif
}

SharedFile::~SharedFile() {
  if (open_ && fd_ >= 0) ::close(fd_);
}

void SharedFile::write_at(std::uint64_t offset, std::string_view bytes) {
  if (!open_ || !error_.empty()) return;
  while (!bytes.empty()) {
    const std::size_t n = std::min(bytes.size(), chunk_bytes);
    std::size_t written = 0;
    if (!uses_mpi()) {
      const ssize_t w = ::pwrite(fd_, bytes.data(), n, static_cast<off_t>(offset));
      if (w < 0) {
        if (errno == EINTR) continue;
        return fail(fmt::format("write failed: {}", std::strerror(errno)));
      }
      written = static_cast<std::size_t>(w);
    } else {
#ifdef YUXI_HAVE_MPI
      MPI_Status status;
      const int code = MPI_File_write_at(to_file(mpi_file_), static_cast<MPI_Offset>(offset),
                                         bytes.data(), static_cast<int>(n), MPI_BYTE, &status);
      int count = 0;
      if (code == MPI_SUCCESS) MPI_Get_count(&status, MPI_BYTE, &count);
      if (code != MPI_SUCCESS || count <= 0)
        return fail(fmt::format("write failed: {}", code == MPI_SUCCESS
                                                        ? std::string("no bytes written")
                                                        : mpi_message(code)));
      written = static_cast<std::size_t>(count);
#endif
    }
    bytes.remove_prefix(written);
    offset += written;
  }
}

std::uint64_t SharedFile::write_in_rank_order(std::uint64_t offset, std::string_view bytes) {
  const std::uint64_t mine = bytes.size();
  write_at(offset + comm_.sum_below(mine), bytes);
  return offset + static_cast<std::uint64_t>(comm_.sum(static_cast<std::int64_t>(mine)));
}

void SharedFile::close(bool durable) {
  if (open_) {
    open_ = false;
    if (!uses_mpi()) {
      if (durable && ::fsync(fd_) != 0)
        fail(fmt::format("cannot flush to disk: {}", std::strerror(errno)));
      if (::close(fd_) != 0) fail(fmt::format("cannot close: {}", std::strerror(errno)));
      fd_ = -1;
    } else {
#ifdef YUXI_HAVE_MPI
      MPI_File file = to_file(mpi_file_);
      if (durable)
        if (const int c = MPI_File_sync(file); c != MPI_SUCCESS)
          fail(fmt::format("cannot flush to disk: {}", mpi_message(c)));
      if (const int c = MPI_File_close(&file); c != MPI_SUCCESS)
        fail(fmt::format("cannot close: {}", mpi_message(c)));
      mpi_file_ = 0;
#endif
    }
  }
  const std::string error = comm_.first_error(error_);
  if (!error.empty()) throw std::runtime_error(error);
}

} // namespace yuxi
