#include "io/toml_reader.hpp"

#include "io/nearest_word.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fmt/format.h>

namespace yuxi {
namespace {

std::string_view type_name(const toml::node& n) {
  switch (n.type()) {
  case toml::node_type::table:
    return "a table";
  case toml::node_type::array:
    return "an array";
  case toml::node_type::string:
    return "a string";
  case toml::node_type::integer:
    return "an integer";
  case toml::node_type::floating_point:
    return "a floating-point number";
  case toml::node_type::boolean:
    return "a boolean";
  default:
    return "a date or time";
  }
}

std::string position(const std::string& file, const toml::source_region& r, bool lines = true) {
  if (r.begin.line == 0 || !lines) return file;
  return fmt::format("{}:{}:{}", file, r.begin.line, r.begin.column);
}

} // namespace

toml::table parse_toml(std::string_view text, const std::string& file) {
  try {
    return toml::parse(text, file);
  } catch (const toml::parse_error& e) {
    throw SceneError(
        fmt::format("{}: syntax error: {}", position(file, e.source()), e.description()));
  }
}

TomlReader::TomlReader(const toml::table& table, std::string path, std::string file, bool lines)
    : table_(&table), path_(std::move(path)), file_(std::move(file)), lines_(lines) {}

std::string TomlReader::key_path(std::string_view key) const {
  return path_.empty() ? std::string(key) : fmt::format("{}.{}", path_, key);
}

std::string TomlReader::where(std::string_view key) const {
  if (const toml::node* n = table_->get(key)) return position(file_, n->source(), lines_);
  return position(file_, table_->source(), lines_);
}

void TomlReader::fail(std::string_view key, std::string_view message) const {
  const std::string name =
      key.empty() ? (path_.empty() ? "scene" : "[" + path_ + "]") : key_path(key);
  const std::string hint = !key.empty() && !has(key) ? misspelling_hint(key) : "";
  throw SceneError(fmt::format("{}: {}: {}{}", where(key), name, message, hint),
                   key.empty() ? path_ : key_path(key));
}

std::string TomlReader::misspelling_hint(std::string_view key) const {
  // A key of the table that nobody asked for and that is nearly this one.
  std::vector<std::string> unasked;
  for (auto&& [k, node] : *table_)
    if (!asked_.contains(k.str())) unasked.emplace_back(k.str());
  const auto near = nearest_word(key, unasked);
  return near ? fmt::format(" (the table has '{}': misspelt?)", *near) : "";
}

void TomlReader::wrong_type(std::string_view key, std::string_view expected) const {
  fail(key, fmt::format("expected {}, got {}", expected, type_name(*table_->get(key))));
}

const toml::node* TomlReader::find(std::string_view key) {
  asked_.emplace(key);
  const toml::node* n = table_->get(key);
  if (n) read_.emplace(key);
  return n;
}

const toml::node& TomlReader::require(std::string_view key) {
  const toml::node* n = find(key);
  if (!n) fail("", fmt::format("missing key '{}'", key) + misspelling_hint(key));
  return *n;
}

double TomlReader::number(std::string_view key) {
  const toml::node& n = require(key);
  const auto v = n.value<double>();
  if (!n.is_number() || !v) wrong_type(key, "a number");
  if (!std::isfinite(*v)) fail(key, "must be finite");
  return *v;
}

double TomlReader::number(std::string_view key, double fallback) {
  return has(key) ? number(key) : fallback;
}

double TomlReader::positive(std::string_view key) {
  const double v = number(key);
  if (!(v > 0.0)) fail(key, fmt::format("must be > 0 (got {})", v));
  return v;
}

double TomlReader::positive(std::string_view key, double fallback) {
  return has(key) ? positive(key) : fallback;
}

double TomlReader::positive_or_infinite(std::string_view key) {
  const toml::node& n = require(key);
  const auto v = n.value<double>();
  if (!n.is_number() || !v) wrong_type(key, "a number");
  if (!(*v > 0.0)) fail(key, fmt::format("must be > 0 (got {})", *v));
  return *v;
}

double TomlReader::non_negative(std::string_view key, double fallback) {
  const double v = number(key, fallback);
  if (v < 0.0) fail(key, fmt::format("must be >= 0 (got {})", v));
  return v;
}

std::int64_t TomlReader::integer(std::string_view key, std::int64_t fallback, std::int64_t min,
                                 std::int64_t max) {
  const toml::node* n = find(key);
  if (!n) return fallback;
  if (!n->is_integer()) wrong_type(key, "an integer");
  const std::int64_t v = *n->value<std::int64_t>();
  if (v < min || v > max) fail(key, fmt::format("must be in [{}, {}] (got {})", min, max, v));
  return v;
}

bool TomlReader::boolean(std::string_view key, bool fallback) {
  const toml::node* n = find(key);
  if (!n) return fallback;
  if (!n->is_boolean()) wrong_type(key, "true or false");
  return *n->value<bool>();
}

std::string TomlReader::string(std::string_view key) {
  const toml::node& n = require(key);
  if (!n.is_string()) wrong_type(key, "a string");
  return *n.value<std::string>();
}

std::string TomlReader::string(std::string_view key, std::string fallback) {
  return has(key) ? string(key) : fallback;
}

std::string TomlReader::plain_name(std::string_view key, std::string_view also,
                                   std::string_view what) {
  std::string name = string(key);
  const bool plain = !name.empty() && std::all_of(name.begin(), name.end(), [&](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || also.find(c) != std::string_view::npos;
  });
  if (!plain) {
    std::string allowed = "letters, digits";
    for (std::size_t k = 0; k < also.size(); ++k)
      allowed += fmt::format("{}'{}'", k + 1 == also.size() ? " and " : ", ", also[k]);
    fail(key, fmt::format("{}: {} only", what, allowed));
  }
  return name;
}

std::string TomlReader::choice(std::string_view key,
                               std::initializer_list<std::string_view> options,
                               std::string_view fallback) {
  return choice(key, std::span<const std::string_view>(options.begin(), options.size()), fallback);
}

std::string TomlReader::choice(std::string_view key, std::span<const std::string_view> options,
                               std::string_view fallback) {
  const std::string v = string(key, std::string(fallback));
  for (auto o : options)
    if (v == o) return v;
  fail(key, fmt::format("unknown value \"{}\" (expected one of: {})", v, fmt::join(options, ", ")));
}

Vec3 TomlReader::vec3(std::string_view key) {
  const toml::node& n = require(key);
  const toml::array* a = n.as_array();
  if (!a || a->size() != 3) wrong_type(key, "an array of 3 numbers");
  Vec3 out;
  for (int k = 0; k < 3; ++k) {
    const auto v = (*a)[static_cast<std::size_t>(k)].value<double>();
    if (!(*a)[static_cast<std::size_t>(k)].is_number() || !v)
      wrong_type(key, "an array of 3 numbers");
    if (!std::isfinite(*v)) fail(key, "must be finite");
    out[k] = *v;
  }
  return out;
}

Vec3 TomlReader::vec3(std::string_view key, Vec3 fallback) {
  return has(key) ? vec3(key) : fallback;
}

std::array<std::int64_t, 3> TomlReader::int3(std::string_view key, std::int64_t min) {
  const toml::node& n = require(key);
  const toml::array* a = n.as_array();
  if (!a || a->size() != 3) wrong_type(key, "an array of 3 integers");
  std::array<std::int64_t, 3> out{};
  for (std::size_t k = 0; k < 3; ++k) {
    if (!(*a)[k].is_integer()) wrong_type(key, "an array of 3 integers");
    out[k] = *(*a)[k].value<std::int64_t>();
    if (out[k] < min) fail(key, fmt::format("entries must be >= {} (got {})", min, out[k]));
  }
  return out;
}

std::vector<std::string> TomlReader::strings(std::string_view key) {
  const toml::node& n = require(key);
  const toml::array* a = n.as_array();
  if (!a) wrong_type(key, "an array of strings");
  std::vector<std::string> out;
  for (const auto& e : *a) {
    if (!e.is_string()) wrong_type(key, "an array of strings");
    out.push_back(*e.value<std::string>());
  }
  return out;
}

std::vector<std::int64_t> TomlReader::integers(std::string_view key) {
  const toml::node& n = require(key);
  const toml::array* a = n.as_array();
  if (!a) wrong_type(key, "an array of integers");
  std::vector<std::int64_t> out;
  for (const auto& e : *a) {
    if (!e.is_integer()) wrong_type(key, "an array of integers");
    out.push_back(*e.value<std::int64_t>());
  }
  return out;
}

std::vector<double> TomlReader::numbers(std::string_view key) {
  const toml::node& n = require(key);
  const toml::array* a = n.as_array();
  if (!a) wrong_type(key, "an array of numbers");
  std::vector<double> out;
  for (const auto& e : *a) {
    if (!e.is_number()) wrong_type(key, "an array of numbers");
    const double x =
        e.is_integer() ? static_cast<double>(*e.value<std::int64_t>()) : *e.value<double>();
    if (!std::isfinite(x)) fail(key, "every number must be finite");
    out.push_back(x);
  }
  return out;
}

std::vector<std::vector<double>> TomlReader::number_rows(std::string_view key, std::size_t width) {
  const std::string what = fmt::format("an array of arrays of {} numbers", width);
  const toml::node& n = require(key);
  const toml::array* rows = n.as_array();
  if (!rows) wrong_type(key, what);
  if (rows->empty()) fail(key, fmt::format("the array is empty: give {}", what));
  std::vector<std::vector<double>> out;
  for (const auto& row : *rows) {
    const toml::array* a = row.as_array();
    if (!a) wrong_type(key, what);
    if (a->size() != width)
      fail(key, fmt::format("row {} has {} numbers, not {}", out.size() + 1, a->size(), width));
    std::vector<double> values;
    for (const auto& e : *a) {
      if (!e.is_number()) wrong_type(key, what);
      const double x =
          e.is_integer() ? static_cast<double>(*e.value<std::int64_t>()) : *e.value<double>();
      if (!std::isfinite(x)) fail(key, "every number must be finite");
      values.push_back(x);
    }
    out.push_back(std::move(values));
  }
  return out;
}

std::optional<TomlReader> TomlReader::table(std::string_view key) {
  const toml::node* n = find(key);
  if (!n) return std::nullopt;
  if (!n->is_table()) wrong_type(key, "a table");
  return TomlReader(*n->as_table(), key_path(key), file_, lines_);
}

std::vector<TomlReader> TomlReader::tables(std::string_view key) {
  std::vector<TomlReader> out;
  const toml::node* n = find(key);
  if (!n) return out;
  const toml::array* a = n->as_array();
  if (!a || !a->is_array_of_tables())
    wrong_type(key, "an array of tables ([[" + std::string(key) + "]])");
  for (std::size_t k = 0; k < a->size(); ++k)
    out.emplace_back(*(*a)[k].as_table(), fmt::format("{}[{}]", key_path(key), k + 1), file_,
                     lines_);
  return out;
}

void TomlReader::finish() const {
  for (auto&& [key, node] : *table_) {
    if (read_.contains(key.str())) continue;
    std::vector<std::string> valid;
    for (const std::string& k : asked_)
      if (!table_->contains(k)) valid.push_back(k);
    const auto near = nearest_word(key.str(), valid);
    throw SceneError(fmt::format("{}: {}: unknown key '{}' ({})",
                                 position(file_, key.source(), lines_), key_path(key.str()),
                                 key.str(),
                                 near ? fmt::format("did you mean '{}'?", *near)
                                      : std::string("misspelt, or not valid here")),
                     key_path(key.str()));
  }
}

} // namespace yuxi
