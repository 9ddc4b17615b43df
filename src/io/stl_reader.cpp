#include "io/stl_reader.hpp"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <system_error>
#include <vector>
#include <zlib.h>

namespace yuxi {
namespace {

constexpr std::uint64_t binary_header = 80 + 4; // the header, then the triangle count
constexpr std::uint64_t binary_triangle = 50;   // normal, 3 vertices, attribute

using Triangle = std::array<Vec3, 3>;

// zlib's CRC-32 of `bytes` (zlib takes uInt lengths, so files over 1 GiB go in chunks).
std::uint32_t crc_of(std::string_view bytes) {
  uLong c = crc32(0L, Z_NULL, 0);
  const auto* p = reinterpret_cast<const Bytef*>(bytes.data());
  std::size_t n = bytes.size();
  while (n > 0) {
    const auto chunk = static_cast<uInt>(std::min<std::size_t>(n, 1u << 30));
    c = crc32(c, p, chunk);
    p += chunk;
    n -= chunk;
  }
  return static_cast<std::uint32_t>(c);
}

std::uint32_t little_endian_u32(const char* p) {
  const auto b = [p](int i) {
    return static_cast<std::uint32_t>(static_cast<unsigned char>(p[i]));
  };
  return b(0) | (b(1) << 8) | (b(2) << 16) | (b(3) << 24);
}

// Zero area: |(b - a) x (c - a)| <= 1e-12 * (longest edge)^2. The vertices are first scaled by a
// power of two (exact) so that neither huge nor tiny coordinates overflow or underflow.
bool degenerate(const Triangle& t) {
  double largest = 0;
  for (const Vec3& v : t)
    for (int k = 0; k < 3; ++k) largest = std::max(largest, std::abs(v[k]));
  if (largest == 0) return true; // three vertices at the origin
  const int e = std::ilogb(largest);
  Triangle s;
  if (e > -1000 && e < 1000) { // 2^-e is a normal double: multiplying by it is exact
    const double scale = std::ldexp(1.0, -e);
    for (int i = 0; i < 3; ++i) s[i] = t[i] * scale;
  } else {
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) s[i][k] = std::ldexp(t[i][k], -e);
  }
  const Vec3 ab = s[1] - s[0], ac = s[2] - s[0], bc = s[2] - s[1];
  const double longest2 = std::max({norm2(ab), norm2(ac), norm2(bc)});
  return norm(cross(ab, ac)) <= 1e-12 * longest2;
}

void add(TriangleSoup& soup, const Triangle& t) {
  if (degenerate(t))
    ++soup.dropped_degenerate;
  else
    soup.triangles.push_back(t);
}

// A word of the file as it may appear in a message: quoted, at most 40 characters, bytes that
// are not printable ASCII written as \xNN.
std::string quoted(std::string_view s) {
  constexpr std::size_t limit = 40;
  std::string out = "\"";
  for (std::size_t i = 0; i < s.size() && i < limit; ++i) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c >= 0x20 && c < 0x7f && c != '"' && c != '\\')
      out += static_cast<char>(c);
    else
      out += fmt::format("\\x{:02x}", c);
  }
  if (s.size() > limit) out += "...";
  return out + '"';
}

// Blanks separate the words of a line: space, tab, carriage return, vertical tab, form feed.
enum CharClass : unsigned char { in_word, blank, newline };
constexpr std::array<CharClass, 256> char_classes = [] {
  std::array<CharClass, 256> c{};
  for (const char b : {' ', '\t', '\r', '\v', '\f'}) c[static_cast<unsigned char>(b)] = blank;
  c['\n'] = newline;
  return c;
}();
CharClass char_class(char c) {
  return char_classes[static_cast<unsigned char>(c)];
}
bool is_blank(char c) {
  return char_class(c) == blank;
}

// ASCII keywords compare without regard to case ("SOLID", "Facet Normal" occur).
bool is(std::string_view word, std::string_view keyword) {
  if (word.size() != keyword.size()) return false;
  for (std::size_t i = 0; i < word.size(); ++i) {
    const char c =
        word[i] >= 'A' && word[i] <= 'Z' ? static_cast<char>(word[i] - 'A' + 'a') : word[i];
    if (c != keyword[i]) return false;
  }
  return true;
}

bool starts_with_solid(std::string_view bytes) {
  if (bytes.starts_with("\xef\xbb\xbf")) bytes.remove_prefix(3); // a UTF-8 byte-order mark
  std::size_t i = 0;
  while (i < bytes.size() && (is_blank(bytes[i]) || bytes[i] == '\n')) ++i;
  return bytes.size() - i >= 5 && is(bytes.substr(i, 5), "solid");
}

// A binary file whose header starts with "solid" and whose count is wrong is read as ASCII and
// fails as such; when the file holds NUL bytes (text never does), the message says what the
// binary reading would have found.
std::string binary_hint(std::string_view bytes) {
  if (std::memchr(bytes.data(), '\0', bytes.size()) == nullptr) return "";
  const std::uint64_t size = bytes.size();
  if (size < binary_header)
    return fmt::format(" (the file holds NUL bytes: if it is a binary STL whose header starts "
                       "with \"solid\", it is truncated: {} bytes, fewer than the {} of the "
                       "header and triangle count)",
                       size, binary_header);
  const std::uint32_t count = little_endian_u32(bytes.data() + 80);
  return fmt::format(" (the file holds NUL bytes: if it is a binary STL whose header starts with "
                     "\"solid\", its header announces {} triangles ({} bytes) but the file "
                     "holds {} bytes)",
                     count, binary_header + binary_triangle * count, size);
}

class AsciiParser {
public:
  AsciiParser(std::string_view bytes, const std::string& source)
      : bytes_(bytes), text_(bytes), source_(source) {
    if (text_.starts_with("\xef\xbb\xbf")) text_.remove_prefix(3);
  }

  void parse(TriangleSoup& soup) {
    bool any_solid = false;
    while (next()) {
      if (!is(word(0), "solid"))
        fail(fmt::format("expected {}, found {}",
                         any_solid ? "another \"solid\" or the end of "
                                     "the file after \"endsolid\""
                                   : "\"solid\"",
                         quoted(line_text_)));
      any_solid = true;
      read_solid(soup, line_);
    }
    if (!any_solid) fail("no \"solid\": the file is empty");
  }

private:
  void read_solid(TriangleSoup& soup, std::size_t solid_line) {
    for (;;) {
      if (!next())
        fail(fmt::format("the file ends inside the solid begun on line {} (no \"endsolid\")",
                         solid_line));
      if (is(word(0), "endsolid")) return; // its name, if any, is not compared
      if (!is(word(0), "facet") || !is(word(1), "normal"))
        fail(
            fmt::format("expected \"facet normal\" or \"endsolid\", found {}", quoted(line_text_)));
      const std::size_t facet_line = line_; // the normal that follows is ignored
      expect_line("outer", "loop", facet_line);
      Triangle t;
      int vertices = 0;
      for (;;) {
        if (!next())
          fail(fmt::format("the file ends inside the facet begun on line {} (expected \"vertex\" "
                           "or \"endloop\")",
                           facet_line));
        if (is(word(0), "endloop") && n_words_ == 1) break;
        if (!is(word(0), "vertex"))
          fail(fmt::format("expected \"vertex\" or \"endloop\", found {}", quoted(line_text_)));
        if (n_words_ != 4)
          fail(fmt::format("a vertex has 3 numbers (x y z), this one {}", n_words_ - 1));
        if (vertices == 3)
          fail(fmt::format("the facet begun on line {} has more than 3 vertices; an STL facet is "
                           "a triangle",
                           facet_line));
        for (int k = 0; k < 3; ++k) t[static_cast<std::size_t>(vertices)][k] = number(word(1 + k));
        ++vertices;
      }
      if (vertices != 3)
        fail(fmt::format("the facet begun on line {} has {} vertices; an STL facet is a triangle "
                         "(3 vertices)",
                         facet_line, vertices));
      expect_line("endfacet", {}, facet_line);
      add(soup, t);
    }
  }

  // The next line that is not blank, split into words; false at the end of the text.
  bool next() {
    const char* p = text_.data() + pos_;
    const char* const end = text_.data() + text_.size();
    while (p < end) {
      ++line_;
      n_words_ = 0;
      const char *first = p, *last = p;
      for (;;) {
        while (p < end && char_class(*p) == blank) ++p;
        if (p == end || *p == '\n') break;
        const char* const start = p;
        while (p < end && char_class(*p) == in_word) ++p;
        if (n_words_ < words_.size())
          words_[n_words_] = std::string_view(start, static_cast<std::size_t>(p - start));
        if (n_words_++ == 0) first = start;
        last = p;
      }
      if (p < end) ++p; // past the newline
      if (n_words_ > 0) {
        pos_ = static_cast<std::size_t>(p - text_.data());
        // For messages: the line without the blanks around it.
        line_text_ = std::string_view(first, static_cast<std::size_t>(last - first));
        return true;
      }
    }
    pos_ = text_.size();
    return false;
  }

  std::string_view word(std::size_t i) const {
    return i < n_words_ ? words_[i] : std::string_view{};
  }

  // The next line must be exactly these keywords ("outer loop", "endfacet").
  void expect_line(std::string_view first, std::string_view second, std::size_t facet_line) {
    const auto wanted = [&] {
      return second.empty() ? std::string(first) : fmt::format("{} {}", first, second);
    };
    if (!next())
      fail(fmt::format("the file ends inside the facet begun on line {} (expected \"{}\")",
                       facet_line, wanted()));
    const std::size_t n = second.empty() ? 1 : 2;
    if (n_words_ != n || !is(word(0), first) || (n == 2 && !is(word(1), second)))
      fail(fmt::format("expected \"{}\", found {}", wanted(), quoted(line_text_)));
  }

  double number(std::string_view s) const {
    const char* begin = s.data();
    const char* const end = s.data() + s.size();
    if (begin != end && *begin == '+' && end - begin > 1 && begin[1] != '-')
      ++begin; // from_chars takes no '+'
    double v = 0;
    const auto [p, ec] = std::from_chars(begin, end, v);
    if (ec == std::errc::result_out_of_range)
      fail(fmt::format("vertex coordinate {} is out of the range of a double", quoted(s)));
    if (ec != std::errc() || p != end)
      fail(fmt::format("vertex coordinate {} is not a number", quoted(s)));
    if (!std::isfinite(v)) fail(fmt::format("vertex coordinate {} is not finite", quoted(s)));
    return v;
  }

  [[noreturn]] void fail(const std::string& message) const {
    throw MeshFileError(
        fmt::format("{}: line {}: {}{}", source_, line_, message, binary_hint(bytes_)));
  }

  std::string_view bytes_; // the whole file
  std::string_view text_;  // without a byte-order mark
  const std::string& source_;
  std::size_t pos_ = 0, line_ = 0;
  std::array<std::string_view, 5> words_;
  std::size_t n_words_ = 0; // may exceed words_.size(): only the first words are kept
  std::string_view line_text_;
};

void parse_binary(std::string_view bytes, const std::string& source, TriangleSoup& soup) {
  const std::uint64_t size = bytes.size();
  if (size < binary_header)
    throw MeshFileError(fmt::format(
        "{}: not an STL file: {} bytes, fewer than the {} of a binary STL's header and triangle "
        "count, and it does not start with \"solid\" as an ASCII STL does",
        source, size, binary_header));
  const std::uint32_t count = little_endian_u32(bytes.data() + 80);
  const std::uint64_t expected = binary_header + binary_triangle * count;
  if (size < expected) {
    const std::uint64_t whole = (size - binary_header) / binary_triangle;
    throw MeshFileError(fmt::format(
        "{}: binary STL truncated: the header announces {} triangles ({} bytes) but the file "
        "holds {} bytes; it ends in triangle {} (byte offset {})",
        source, count, expected, size, whole + 1, binary_header + binary_triangle * whole));
  }
  if (size > expected)
    throw MeshFileError(fmt::format(
        "{}: binary STL with a wrong triangle count: the header announces {} triangles ({} "
        "bytes) but the file holds {} bytes, {} after the last triangle",
        source, count, expected, size, size - expected));
  soup.triangles.reserve(count); // the count matches the file's size
  for (std::uint32_t i = 0; i < count; ++i) {
    const std::uint64_t offset = binary_header + binary_triangle * i;
    const char* p = bytes.data() + offset + 12; // past the normal
    Triangle t;
    for (std::size_t v = 0; v < 3; ++v)
      for (int k = 0; k < 3; ++k, p += 4) {
        const float x = std::bit_cast<float>(little_endian_u32(p));
        if (!std::isfinite(x))
          throw MeshFileError(fmt::format(
              "{}: triangle {} of {} (byte offset {}): vertex {} has a coordinate that is not "
              "finite ({})",
              source, i + 1, count, offset, v + 1, x));
        t[v][k] = x;
      }
    add(soup, t);
  }
}

} // namespace

TriangleSoup parse_stl(std::string_view bytes, const std::string& source_name) {
  TriangleSoup soup;
  soup.bytes = bytes.size();
  soup.crc32 = crc_of(bytes);
  const std::uint64_t size = bytes.size();
  // Binary when the count fits the size exactly, even after a header that starts with "solid".
  const bool sized_as_binary =
      size >= binary_header &&
      size == binary_header + binary_triangle * little_endian_u32(bytes.data() + 80);
  if (!sized_as_binary && starts_with_solid(bytes)) {
    AsciiParser(bytes, source_name).parse(soup);
  } else {
    parse_binary(bytes, source_name, soup);
  }
  if (soup.triangles.empty()) {
    if (soup.dropped_degenerate == 0)
      throw MeshFileError(fmt::format("{}: the mesh holds no triangles", source_name));
    throw MeshFileError(
        fmt::format("{}: the mesh is empty: all {} of its triangles have zero area (degenerate)",
                    source_name, soup.dropped_degenerate));
  }
  return soup;
}

TriangleSoup read_stl(const std::string& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status))
    throw MeshFileError(fmt::format("{}: cannot read the STL file: no such file", path));
  if (std::filesystem::is_directory(status))
    throw MeshFileError(fmt::format("{}: cannot read the STL file: it is a directory", path));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw MeshFileError(fmt::format("{}: cannot open the STL file", path));
  std::string bytes;
  if (std::filesystem::is_regular_file(status)) {
    const auto size = std::filesystem::file_size(path, ec);
    if (!ec) bytes.reserve(size);
  }
  std::vector<char> buffer(1 << 16);
  for (;;) {
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    bytes.append(buffer.data(), static_cast<std::size_t>(in.gcount()));
    if (!in) break;
  }
  if (in.bad())
    throw MeshFileError(fmt::format("{}: cannot read the STL file: a read error after {} bytes",
                                    path, bytes.size()));
  return parse_stl(bytes, path);
}

} // namespace yuxi
