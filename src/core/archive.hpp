// Binary archives for checkpoints. A plain record (a part of the state with no layout history)
// describes itself in one templated function that both saves (ArchiveWriter) and loads
// (ArchiveReader), so the two directions cannot drift apart (the GROMACS modular simulator's
// approach). A part whose section changed with the state layout (sim/state_layout.hpp) has a
// const save() and a load(reader, layout) of its own. Values are stored in the machine's byte
// order; the checkpoint header records it.
#pragma once

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace yuxi {

class ArchiveError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

class ArchiveWriter {
public:
  static constexpr bool loading = false;

  template <class T> void value(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes(&v, sizeof v);
  }
  // n elements starting at data.
  template <class T> void elements(const T* data, std::uint64_t n) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes(data, n * sizeof(T));
  }
  template <class T> void vector(const std::vector<T>& v) {
    const std::uint64_t n = v.size();
    value(n);
    elements(v.data(), n);
  }
  void string(const std::string& s) {
    const std::uint64_t n = s.size();
    value(n);
    bytes(s.data(), n);
  }
  const std::string& data() const { return buffer_; }
  // Hands the bytes over (the writer is empty after).
  std::string release() { return std::move(buffer_); }

private:
  void bytes(const void* p, std::size_t n) { buffer_.append(static_cast<const char*>(p), n); }
  std::string buffer_;
};

class ArchiveReader {
public:
  static constexpr bool loading = true;
  explicit ArchiveReader(std::string_view data) : data_(data) {}

  template <class T> void value(T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    take(&v, sizeof v);
  }
  template <class T> void elements(T* data, std::uint64_t n) {
    static_assert(std::is_trivially_copyable_v<T>);
    check_room(n, sizeof(T));
    take(data, n * sizeof(T));
  }
  template <class T> void vector(std::vector<T>& v) {
    std::uint64_t n = 0;
    value(n);
    check_room(n, sizeof(T));
    v.resize(n);
    elements(v.data(), n);
  }
  void string(std::string& s) {
    std::uint64_t n = 0;
    value(n);
    check_room(n, 1);
    s.assign(data_.substr(pos_, n));
    pos_ += n;
  }
  // Refuses a count that the remaining bytes cannot hold (a corrupt length field).
  void check_room(std::uint64_t n, std::size_t size) const {
    if (size != 0 && n > (data_.size() - pos_) / size)
      throw ArchiveError("a length field exceeds the data that follows (corrupt or truncated)");
  }
  bool at_end() const { return pos_ == data_.size(); }
  // Passes over whatever is left (a part of the state the reader does not take).
  void skip_to_end() { pos_ = data_.size(); }

private:
  void take(void* p, std::size_t n) {
    if (n > data_.size() - pos_) throw ArchiveError("the data ends early (truncated)");
    if (n) std::memcpy(p, data_.data() + pos_, n);
    pos_ += n;
  }
  std::string_view data_;
  std::size_t pos_ = 0;
};

} // namespace yuxi
