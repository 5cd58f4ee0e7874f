#include "core/glb_container.h"

#include <gtest/gtest.h>

#include "core/error.h"

namespace cinepath {
namespace {

TEST(GlbContainer, AssembledChunksSplitBackPadded) {
  const std::string glb = AssembleGlb(R"({"asset":{"version":"2.0"}})", std::string("\x01\x02\x03", 3));
  EXPECT_EQ(glb.size() % 4, 0u);
  const GlbChunks chunks = SplitGlb(glb, "a.glb");
  EXPECT_EQ(chunks.json.size() % 4, 0u);
  EXPECT_EQ(chunks.json.substr(0, 27), R"({"asset":{"version":"2.0"}})");
  EXPECT_EQ(chunks.bin, std::string("\x01\x02\x03\x00", 4));
  EXPECT_TRUE(SplitGlb(AssembleGlb("{}", ""), "b.glb").bin.empty());
}

TEST(GlbContainer, TruncatedOrForeignFilesAreInputErrors) {
  const std::string glb = AssembleGlb("{}", "abcd");
  EXPECT_THROW(SplitGlb(glb.substr(0, glb.size() - 4), "a.glb"), InputError);
  EXPECT_THROW(SplitGlb("PK\x03\x04 not a glb", "a.glb"), InputError);
  std::string long_chunk = glb;
  long_chunk[12] = '\x7f';  // the JSON chunk claims more than the file holds
  EXPECT_THROW(SplitGlb(long_chunk, "a.glb"), InputError);
}

}  // namespace
}  // namespace cinepath
