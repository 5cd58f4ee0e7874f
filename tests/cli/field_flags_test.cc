#include "cli/field_flags.h"

#include <gtest/gtest.h>

namespace cinepath::cli {
namespace {

const FieldFlags kFlags = {{"target_faces", "--target-faces"},
                           {"max_error_m", "--max-error-m"},
                           {"formats", "--format"},
                           {"scene_origin", "--scene"}};

TEST(FieldFlags, TheLocationNamesTheFlag) {
  EXPECT_EQ(WithFlagNames("target_faces: must be > 0", kFlags), "--target-faces: must be > 0");
  EXPECT_EQ(WithFlagNames("target_faces and max_error_m: give at most one of them", kFlags),
            "--target-faces and --max-error-m: give at most one of them");
}

TEST(FieldFlags, OnlyWholeWordsInTheLocationAndQuotedFieldsElsewhere) {
  // "formats" in the text after the location is left alone; a backticked field is mapped.
  EXPECT_EQ(WithFlagNames("plan.json: origin: no formats here; pass `scene_origin`", kFlags),
            "plan.json: origin: no formats here; pass --scene");
  EXPECT_EQ(WithFlagNames("my_target_faces: x", kFlags), "my_target_faces: x");
  EXPECT_EQ(WithFlagNames("no location at all", kFlags), "no location at all");
  EXPECT_EQ(WithFlagNames("--target-faces: already a flag", kFlags), "--target-faces: already a flag");
}

}  // namespace
}  // namespace cinepath::cli
