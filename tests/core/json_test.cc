#include "core/json.h"

#include <cmath>
#include <limits>

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

}  // namespace
}  // namespace cinepath
