#include "core/json.h"

#include <cmath>
#include <fstream>
#include <sstream>
#include <type_traits>

#include <simdjson.h>

#include "core/error.h"
#include "core/file_io.h"
#include "core/number_format.h"

namespace cinepath {
namespace {

void RequireFinite(const Json& node, const std::string& path) {
  if (node.is_number_float()) {
    if (!std::isfinite(node.get<double>())) {
      throw InternalError("JSON writer: non-finite number at " + (path.empty() ? "/" : path));
    }
  } else if (node.is_object()) {
    for (const auto& [key, value] : node.items()) RequireFinite(value, path + "/" + key);
  } else if (node.is_array()) {
    for (size_t i = 0; i < node.size(); ++i) RequireFinite(node[i], path + "/" + std::to_string(i));
  }
}

std::string TypeName(const Json& node) {
  if (node.is_null()) return "null";
  if (node.is_boolean()) return "a boolean";
  if (node.is_number()) return "a number";
  if (node.is_string()) return "a string";
  if (node.is_array()) return "an array";
  return "an object";
}

}  // namespace

std::string DumpJson(const Json& document) {
  RequireFinite(document, "");
  std::string text = document.dump(2, ' ', /*ensure_ascii=*/false, nlohmann::json::error_handler_t::strict);
  text.push_back('\n');
  return text;
}

double RoundToDecimals(double value, int decimals) {
  if (!std::isfinite(value)) return value;
  const double scale = std::pow(10.0, decimals);
  const double rounded = std::round(value * scale) / scale;
  return rounded == 0.0 ? 0.0 : rounded;  // no "-0.0" in outputs
}

namespace {

// "line L, column C" of a byte offset (1-based, counting bytes).
std::string LineColumn(std::string_view text, size_t byte) {
  size_t line = 1, column = 1;
  for (size_t i = 0; i + 1 < byte && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

// nlohmann's DOM builder, except that every parse error (syntax, and numbers out of range such as
// 1e400, which the plain parser reports without a position) becomes an InputError naming the file,
// the line and the column.
class LocatedDomParser : public nlohmann::detail::json_sax_dom_parser<Json> {
 public:
  LocatedDomParser(Json& result, std::string_view text, const std::string& source)
      : json_sax_dom_parser(result, /*allow_exceptions=*/true), text_(text), source_(source) {}

  template <class Exception>
  bool parse_error(std::size_t position, const std::string& last_token, const Exception& ex) {
    // A number out of range is reported at its first character, a syntax error where reading stopped.
    if (std::is_same_v<Exception, nlohmann::json::out_of_range> && position >= last_token.size()) {
      position -= last_token.size() - 1;
    }
    std::string what = ex.what();
    if (const auto pos = what.find("] "); what.rfind("[json.exception.", 0) == 0 && pos != std::string::npos) {
      what = what.substr(pos + 2);  // drop "[json.exception.parse_error.101] "
    }
    if (const auto pos = what.find("syntax error"); pos != std::string::npos) what = what.substr(pos);
    throw InputError(source_ + ": " + LineColumn(text_, position) + ": invalid JSON: " + what);
  }

 private:
  std::string_view text_;
  const std::string& source_;
};

// simdjson's DOM copied into nlohmann's, node for node, as nlohmann's own parser would have built it:
// integers without a sign as unsigned, with one as signed, any other number a double, a key met twice
// keeping its first place and its last value. False where the two parsers could disagree, so that
// nlohmann reads the text itself: a "-0" (simdjson reads it as the double -0.0, nlohmann as the integer
// 0) and a string that is not valid UTF-8 (an escaped lone surrogate).
bool CopyDom(const simdjson::dom::element& from, Json* to) {
  using Type = simdjson::dom::element_type;
  switch (from.type()) {
    case Type::ARRAY: {
      const simdjson::dom::array array = from.get_array().value_unsafe();
      *to = Json::array();
      auto& elements = to->get_ref<Json::array_t&>();
      elements.reserve(array.size());
      for (const simdjson::dom::element element : array) {
        if (!CopyDom(element, &elements.emplace_back())) return false;
      }
      return true;
    }
    case Type::OBJECT: {
      const simdjson::dom::object object = from.get_object().value_unsafe();
      *to = Json::object();
      auto& members = to->get_ref<Json::object_t&>();
      for (const simdjson::dom::key_value_pair member : object) {
        if (!simdjson::validate_utf8(member.key.data(), member.key.size())) return false;
        if (!CopyDom(member.value, &members[std::string(member.key)])) return false;
      }
      return true;
    }
    case Type::INT64: {
      const int64_t value = from.get_int64().value_unsafe();
      *to = value >= 0 ? Json(Json::number_unsigned_t(value)) : Json(Json::number_integer_t(value));
      return true;
    }
    case Type::UINT64: *to = Json::number_unsigned_t(from.get_uint64().value_unsafe()); return true;
    case Type::DOUBLE: {
      const double value = from.get_double().value_unsafe();
      if (value == 0.0 && std::signbit(value)) return false;
      *to = value;
      return true;
    }
    case Type::STRING: {
      const std::string_view value = from.get_string().value_unsafe();
      if (!simdjson::validate_utf8(value.data(), value.size())) return false;
      *to = std::string(value);
      return true;
    }
    case Type::BOOL: *to = from.get_bool().value_unsafe(); return true;
    case Type::NULL_VALUE: *to = nullptr; return true;
  }
  return false;
}

}  // namespace

// simdjson parses and its DOM is copied into nlohmann's (a 1 MB plan.json: 45 M instructions with the copy
// against nlohmann's 125 M, a tenth of a one-frame render; docs/render.md, "Start-up"). Any text simdjson does not
// take, or that the copy cannot vouch for, is parsed again by nlohmann, whose verdict stands: its result, or its error
// with the line and the column.
Json ParseJsonText(std::string_view text, const std::string& source_name) {
  {
    simdjson::dom::parser fast;
    simdjson::dom::element root;
    Json result;
    if (fast.parse(text.data(), text.size()).get(root) == simdjson::SUCCESS && CopyDom(root, &result)) {
      return result;
    }
  }
  Json result;
  LocatedDomParser parser(result, text, source_name);
  Json::sax_parse(text.begin(), text.end(), &parser);
  return result;
}

Json ParseJsonFile(const std::filesystem::path& path) { return ParseJsonText(ReadFileToString(path), path.string()); }

JsonField::JsonField(const Json& node, std::string source, std::string path)
    : node_(&node), source_(std::move(source)), path_(std::move(path)) {}

std::string JsonField::Where() const {
  if (path_.empty()) return source_;
  return source_.empty() ? path_ : source_ + ": " + path_;
}

void JsonField::Fail(const std::string& what) const { throw InputError(Located(Where(), what)); }

JsonField JsonField::operator[](std::string_view key) const {
  if (!node_->is_object()) Fail("expected an object, found " + TypeName(*node_));
  const std::string child_path = path_.empty() ? std::string(key) : path_ + "." + std::string(key);
  auto it = node_->find(std::string(key));
  if (it == node_->end()) {
    throw InputError(Located(source_.empty() ? child_path : source_ + ": " + child_path, "missing (required)"));
  }
  return JsonField(*it, source_, child_path);
}

std::optional<JsonField> JsonField::Find(std::string_view key) const {
  if (!node_->is_object()) Fail("expected an object, found " + TypeName(*node_));
  auto it = node_->find(std::string(key));
  if (it == node_->end() || it->is_null()) return std::nullopt;
  const std::string child_path = path_.empty() ? std::string(key) : path_ + "." + std::string(key);
  return JsonField(*it, source_, child_path);
}

bool JsonField::Has(std::string_view key) const { return Find(key).has_value(); }

JsonField JsonField::At(size_t index) const {
  if (!node_->is_array()) Fail("expected an array, found " + TypeName(*node_));
  if (index >= node_->size()) Fail("index " + std::to_string(index) + " out of range");
  return JsonField((*node_)[index], source_, path_ + "[" + std::to_string(index) + "]");
}

std::vector<JsonField> JsonField::Elements() const {
  if (!node_->is_array()) Fail("expected an array, found " + TypeName(*node_));
  std::vector<JsonField> out;
  out.reserve(node_->size());
  for (size_t i = 0; i < node_->size(); ++i) out.push_back(At(i));
  return out;
}

size_t JsonField::size() const { return node_->size(); }

double JsonField::AsDouble() const {
  if (!node_->is_number()) Fail("expected a number, found " + TypeName(*node_));
  const double v = node_->get<double>();
  if (!std::isfinite(v)) Fail("must be finite");
  return v;
}

double JsonField::AsPositive() const {
  const double v = AsDouble();
  if (!(v > 0)) Fail("must be > 0");
  return v;
}

double JsonField::AsNonNegative() const {
  const double v = AsDouble();
  if (!(v >= 0)) Fail("must be >= 0");
  return v;
}

double JsonField::AsDoubleIn(double lo, double hi) const {
  const double v = AsDouble();
  if (!(v >= lo && v <= hi)) Fail("must be in [" + FormatSignificant(lo) + ", " + FormatSignificant(hi) + "]");
  return v;
}

int64_t JsonField::AsInt() const {
  if (node_->is_number_integer()) return node_->get<int64_t>();
  if (node_->is_number_float()) {
    const double v = node_->get<double>();
    if (std::isfinite(v) && v == std::floor(v) && std::fabs(v) < 9e15) return static_cast<int64_t>(v);
  }
  Fail("expected an integer, found " + TypeName(*node_));
}

bool JsonField::AsBool() const {
  if (!node_->is_boolean()) Fail("expected true or false, found " + TypeName(*node_));
  return node_->get<bool>();
}

std::string JsonField::AsString() const {
  if (!node_->is_string()) Fail("expected a string, found " + TypeName(*node_));
  return node_->get<std::string>();
}

double JsonField::DoubleOr(std::string_view key, double fallback) const {
  auto f = Find(key);
  return f ? f->AsDouble() : fallback;
}

std::string JsonField::StringOr(std::string_view key, const std::string& fallback) const {
  auto f = Find(key);
  return f ? f->AsString() : fallback;
}

bool JsonField::BoolOr(std::string_view key, bool fallback) const {
  auto f = Find(key);
  return f ? f->AsBool() : fallback;
}

void JsonField::RejectUnknownKeys(std::initializer_list<std::string_view> known) const {
  RejectUnknownKeys(std::vector<std::string_view>(known));
}

void JsonField::RejectUnknownKeys(const std::vector<std::string_view>& known, const std::string& what) const {
  if (!node_->is_object()) Fail("expected an object, found " + TypeName(*node_));
  for (const auto& item : node_->items()) {
    bool ok = false;
    for (auto k : known) ok = ok || (k == item.key());
    if (!ok) {
      const std::string child = path_.empty() ? item.key() : path_ + "." + item.key();
      throw InputError(Located(source_.empty() ? child : source_ + ": " + child, what));
    }
  }
}

}  // namespace cinepath
