#include "core/quality.h"

#include <gtest/gtest.h>

#include "core/error.h"

namespace cinepath {
namespace {

TEST(Quality, EveryNameParsesBackToItsRungCheapestFirst) {
  const std::vector<Quality> rungs = {Quality::kDraft, Quality::kStandard, Quality::kFinal};
  ASSERT_EQ(QualityNames().size(), rungs.size());
  for (size_t i = 0; i < rungs.size(); ++i) {
    EXPECT_EQ(QualityNames()[i], QualityName(rungs[i]));
    EXPECT_EQ(ParseQuality(QualityNames()[i]), rungs[i]);
  }
}

TEST(Quality, AnythingElseIsAnInputErrorNamingWhereItCameFrom) {
  for (const std::string bad : {"best", "Draft", "", "final "}) {
    try {
      ParseQuality(bad, "render.json: quality");
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("render.json: quality"), std::string::npos) << what;
      EXPECT_NE(what.find("'" + bad + "'"), std::string::npos) << what;
    }
  }
}

}  // namespace
}  // namespace cinepath
