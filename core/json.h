// Deterministic JSON for every file cinepath writes, and path-aware reading for every file it reads.
//
// Writing: keys stay in insertion order (nlohmann::ordered_json), two-space indent, a final newline,
// doubles in the shortest form that round-trips (Grisu2, as nlohmann prints them), integers as
// integers. NaN and infinity are refused (JSON has no spelling for them): write null on purpose.
// Reading: JsonField carries the file name and the JSON path of the node, so every complaint reads
// like "shots.json: shots[2].radius_m: must be > 0".
#pragma once

#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace cinepath {

using Json = nlohmann::ordered_json;

// The one serializer: 2-space indent, shortest round-trip doubles, trailing newline.
// Throws InternalError if the document holds NaN or infinity.
std::string DumpJson(const Json& document);

// Rounds to a fixed number of decimals (a documented output precision for derived values).
double RoundToDecimals(double value, int decimals);

// Parses a file / a text. Syntax errors become InputError("<source>: line L, column C: ...").
Json ParseJsonFile(const std::filesystem::path& path);
Json ParseJsonText(std::string_view text, const std::string& source_name);

class JsonField {
 public:
  JsonField(const Json& node, std::string source, std::string path = "");

  // Members and elements. operator[] requires the key (InputError "missing"); Find returns
  // nullopt when the key is absent or null.
  JsonField operator[](std::string_view key) const;
  std::optional<JsonField> Find(std::string_view key) const;
  bool Has(std::string_view key) const;
  JsonField At(size_t index) const;
  std::vector<JsonField> Elements() const;  // requires an array
  size_t size() const;

  bool IsNull() const { return node_->is_null(); }
  bool IsNumber() const { return node_->is_number(); }
  bool IsString() const { return node_->is_string(); }
  bool IsObject() const { return node_->is_object(); }
  bool IsArray() const { return node_->is_array(); }

  // Typed reads; each throws InputError naming the path on a wrong type or a non-finite number.
  double AsDouble() const;
  double AsPositive() const;                      // > 0
  double AsNonNegative() const;                   // >= 0
  double AsDoubleIn(double lo, double hi) const;  // in [lo, hi], else "must be in [lo, hi]"
  int64_t AsInt() const;
  bool AsBool() const;
  std::string AsString() const;

  // Optional typed reads with defaults.
  double DoubleOr(std::string_view key, double fallback) const;
  std::string StringOr(std::string_view key, const std::string& fallback) const;
  bool BoolOr(std::string_view key, bool fallback) const;

  // Fails on any member not listed (catches typos such as "raduis_m"): "<where>.<key>: <what>".
  void RejectUnknownKeys(std::initializer_list<std::string_view> known) const;
  void RejectUnknownKeys(const std::vector<std::string_view>& known, const std::string& what = "unknown key") const;

  [[noreturn]] void Fail(const std::string& what) const;  // InputError("<source>: <path>: what")

  const Json& node() const { return *node_; }
  const std::string& path() const { return path_; }
  const std::string& source() const { return source_; }
  std::string Where() const;  // "<source>: <path>"

 private:
  const Json* node_;
  std::string source_;
  std::string path_;
};

}  // namespace cinepath
