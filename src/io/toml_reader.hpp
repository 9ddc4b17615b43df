// Typed, validated access to one TOML table that remembers which keys were read, so that
// finish() can reject the keys nobody asked for (a misspelt key is an error, not a silent
// default). Every error names the file, line, column and the full key path.
#pragma once

#include "core/vec3.hpp"
#include "io/scene_error.hpp"

#include <array>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <string_view>
#include <toml++/toml.h>
#include <vector>

namespace yuxi {

class TomlReader {
public:
  // `lines`: the text is one the user wrote (a file, a string), so errors give its line and
  // column; a text made from a dict (Python) gives the key's path alone.
  TomlReader(const toml::table& table, std::string path, std::string file, bool lines = true);

  bool has(std::string_view key) const {
    asked_.emplace(key);
    return table_->contains(key);
  }

  double number(std::string_view key);
  double number(std::string_view key, double fallback);
  double positive(std::string_view key);
  double positive(std::string_view key, double fallback);
  double positive_or_infinite(std::string_view key); // > 0; inf allowed (a rigid body)
  double non_negative(std::string_view key, double fallback);
  std::int64_t integer(std::string_view key, std::int64_t fallback, std::int64_t min,
                       std::int64_t max);
  bool boolean(std::string_view key, bool fallback);
  std::string string(std::string_view key);
  std::string string(std::string_view key, std::string fallback);
  // A required name of letters, digits and the characters of `also` only; else fails, saying
  // that it must be `what` (a CSV column's name, a folder's name).
  std::string plain_name(std::string_view key, std::string_view also, std::string_view what);
  std::string choice(std::string_view key, std::initializer_list<std::string_view> options,
                     std::string_view fallback);
  std::string choice(std::string_view key, std::span<const std::string_view> options,
                     std::string_view fallback);
  Vec3 vec3(std::string_view key);
  Vec3 vec3(std::string_view key, Vec3 fallback);
  std::array<std::int64_t, 3> int3(std::string_view key, std::int64_t min);
  std::vector<std::string> strings(std::string_view key);
  std::vector<std::int64_t> integers(std::string_view key);
  std::vector<double> numbers(std::string_view key); // finite numbers (integers allowed)
  // An array of arrays of `width` finite numbers each ([[x, y, z, r], ...]); at least one.
  std::vector<std::vector<double>> number_rows(std::string_view key, std::size_t width);

  std::optional<TomlReader> table(std::string_view key);
  std::vector<TomlReader> tables(std::string_view key); // an array of tables ([[key]])

  // Throws on the first key that was never read, naming the key asked for that it is nearest
  // (a misspelling).
  void finish() const;

  // An error located at `key` (or at this table when the key is absent).
  [[noreturn]] void fail(std::string_view key, std::string_view message) const;
  std::string where(std::string_view key) const;
  std::string key_path(std::string_view key) const;
  const std::string& path() const { return path_; }

private:
  const toml::node& require(std::string_view key);
  const toml::node* find(std::string_view key);
  [[noreturn]] void wrong_type(std::string_view key, std::string_view expected) const;
  // " (the table has 'radious': misspelt?)" where a key nobody asked for is nearly `key`.
  std::string misspelling_hint(std::string_view key) const;

  const toml::table* table_;
  std::string path_;
  std::string file_;
  bool lines_ = true;
  std::set<std::string, std::less<>> read_;
  mutable std::set<std::string, std::less<>> asked_; // every key asked for, read or not
};

// Parses a TOML document; syntax errors become SceneError with file:line:column.
toml::table parse_toml(std::string_view text, const std::string& file);

} // namespace yuxi
