#include "core/json.h"

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"

namespace cinepath {
namespace {

TEST(Json, DumpKeepsKeyOrderAndShortestDoubles) {
  Json j;
  j["zeta"] = 1;
  j["alpha"] = 0.1;
  j["mid"] = {{"b", 2.5}, {"a", nullptr}};
  j["third"] = 1.0 / 3.0;
  EXPECT_EQ(DumpJson(j),
            "{\n  \"zeta\": 1,\n  \"alpha\": 0.1,\n  \"mid\": {\n    \"b\": 2.5,\n    \"a\": null\n  },\n"
            "  \"third\": 0.3333333333333333\n}\n");
}

TEST(Json, DumpRefusesNonFinite) {
  Json j;
  j["x"] = {1.0, std::numeric_limits<double>::quiet_NaN()};
  EXPECT_THROW(DumpJson(j), InternalError);
  j["x"] = std::numeric_limits<double>::infinity();
  EXPECT_THROW(DumpJson(j), InternalError);
}

TEST(Json, RoundToDecimals) {
  EXPECT_EQ(RoundToDecimals(29.811904761904, 2), 29.81);
  EXPECT_EQ(RoundToDecimals(-0.0000001, 3), 0.0);
  EXPECT_FALSE(std::signbit(RoundToDecimals(-0.0000001, 3)));
}

TEST(Json, SyntaxErrorNamesLineAndColumn) {
  try {
    ParseJsonText("{\n  \"a\": 1,\n  \"b\": ]\n}", "shots.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("shots.json: line 3, column"), std::string::npos) << e.what();
  }
}

TEST(Json, FieldErrorsNameThePath) {
  const Json doc = ParseJsonText(R"({"shots": [{"radius_m": 5}, {"radius_m": -2, "typo": 1}]})", "s.json");
  JsonField root(doc, "s.json");
  EXPECT_DOUBLE_EQ(root["shots"].At(0)["radius_m"].AsPositive(), 5);
  try {
    root["shots"].At(1)["radius_m"].AsPositive();
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "s.json: shots[1].radius_m: must be > 0");
  }
  try {
    root["shots"].At(1)["height_m"];
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "s.json: shots[1].height_m: missing (required)");
  }
  try {
    root["shots"].At(1).RejectUnknownKeys({"radius_m"});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "s.json: shots[1].typo: unknown key");
  }
  EXPECT_THROW(root["shots"].AsDouble(), InputError);
  EXPECT_EQ(root["shots"].At(0).DoubleOr("height_m", 7.5), 7.5);
  EXPECT_FALSE(root["shots"].At(0).Find("nothing"));
}

TEST(Json, IntegersAndBooleans) {
  const Json doc = ParseJsonText(R"({"n": 3, "f": 3.0, "g": 3.5, "b": true})", "x");
  JsonField r(doc, "x");
  EXPECT_EQ(r["n"].AsInt(), 3);
  EXPECT_EQ(r["f"].AsInt(), 3);
  EXPECT_THROW(r["g"].AsInt(), InputError);
  EXPECT_TRUE(r["b"].AsBool());
  EXPECT_THROW(r["n"].AsBool(), InputError);
}

TEST(Json, NumbersOutOfRangeAreBadInputWithTheirPosition) {
  // 2026-11 (found from outside): "1e400" escaped as nlohmann's out_of_range.406 without a position.
  try {
    ParseJsonText("{\"a\": [1, 2,\n  1e400]}", "shots.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "shots.json: line 2, column 3: invalid JSON: number overflow parsing '1e400'");
  }
  EXPECT_THROW(ParseJsonText("[-1e999]", "x.json"), InputError);
}

// ParseJsonText reads through simdjson and copies its tree into nlohmann's: the tree must be the one
// nlohmann's own parser builds, node types included, above all where the two parsers differ.
TEST(Json, FastParseBuildsNlohmannsOwnTree) {
  const std::vector<std::string> texts = {
      R"({"b": 1, "a": [1.5, -2, 3e2, 0, -0.0, 1e-400, 18446744073709551615]})",
      R"([9223372036854775808, -9223372036854775808, 2.2250738585072011e-308, 0.1e1])",
      R"({"k": 1, "j": 2, "k": {"x": null}})",        // a key twice: its first place, its last value
      R"([-0, 0, "-0", true, false, null, {}, []])",  // "-0": the integer 0 for nlohmann, -0.0 for simdjson
      R"(["\u00e9\ud83d\ude00", "tab\tnew\nline", "\u0000"])",
      R"(123456789012345678901234567890)",              // beyond 64 bits: a double for nlohmann
      "\xEF\xBB\xBF{\"bom\": 1}",                       // a UTF-8 byte-order mark
      std::string(1500, '[') + std::string(1500, ']'),  // deeper than simdjson's 1,024 levels
  };
  for (const std::string& text : texts) {
    SCOPED_TRACE(text.substr(0, 80));
    const Json ours = ParseJsonText(text, "x.json");
    const Json theirs = Json::parse(text);
    EXPECT_EQ(ours, theirs);
    EXPECT_EQ(ours.dump(), theirs.dump());  // the same node types too (an integer 0 prints "0", -0.0 "-0.0")
  }
  const Json numbers = ParseJsonText(R"([7, -7, 7.0, 18446744073709551615])", "x.json");
  EXPECT_TRUE(numbers[0].is_number_unsigned());
  EXPECT_TRUE(numbers[1].is_number_integer() && !numbers[1].is_number_unsigned());
  EXPECT_TRUE(numbers[2].is_number_float());
  EXPECT_TRUE(numbers[3].is_number_unsigned());
  const Json keys = ParseJsonText(R"({"k": 1, "j": 2, "k": 3})", "x.json");
  EXPECT_EQ(keys.begin().key(), "k");
  EXPECT_EQ(keys["k"], 3);
}

TEST(Json, FastParseLeavesBadTextToNlohmannsLocatedErrors) {
  for (const char* text : {R"({"a": "\ud800"})", R"({"a": "\udc00x"})", "{\"a\": \"\xC3\x28\"}", R"({"a": 1,})",
                           R"({"a": 1} x)", "", R"([1e400])", R"({"a": "x)"}) {
    SCOPED_TRACE(text);
    EXPECT_THROW(ParseJsonText(text, "x.json"), InputError);
    EXPECT_THROW({ const Json parsed = Json::parse(text); }, Json::exception);
  }
  try {
    ParseJsonText("{\"a\": 1,\n \"b\": tru}", "plan.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("plan.json: line 2, column"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace cinepath
