// The stage list's declarations (gpu/stage_list.hpp): refused naming the stage and the resource
// at fault; the barriers it places are exercised by the image pipeline's tests (EchoImageGpu*, on
// lavapipe with validation on: a missing barrier or a wrong layout is a validation message there).
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "gpu/stage_list.hpp"

namespace echosim::gpu {
namespace {

constexpr auto kCompute = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;

std::string refusal(std::vector<StageResourceDecl> resources, std::vector<StageDecl> stages)
{
    try {
        StageList list(std::move(resources), std::move(stages));
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    return "";
}

TEST(StageList, DeclarationsAreCheckedNamingTheStageAndTheResource)
{
    const StageList ok({{"map"}, {"image", true}},
                       {{"solve", {}, {{0, kCompute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT}}},
                        {"copy", {{0, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT}},
                         {{1, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, true}}}});
    EXPECT_EQ(ok.size(), 2u);
    EXPECT_EQ(ok.stage_index("copy"), 1);
    EXPECT_EQ(ok.stage_index("b-mode"), -1);

    std::string why = refusal({{"map"}}, {{"solve", {}, {{3, kCompute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT}}}});
    EXPECT_NE(why.find("stage 'solve': resource 3 is not declared"), std::string::npos) << why;
    why = refusal({{"image", true}}, {{"copy", {}, {{0, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT}}}});
    EXPECT_NE(why.find("stage 'copy': resource 'image': an image needs the layout"), std::string::npos) << why;
    why = refusal({{"map"}}, {{"slice", {{0, kCompute, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, VK_IMAGE_LAYOUT_GENERAL}}, {}}});
    EXPECT_NE(why.find("stage 'slice': resource 'map': a buffer has no layout"), std::string::npos) << why;
    why = refusal({{"map"}}, {{"slice", {{0, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT}}, {}}});
    EXPECT_NE(why.find("no pipeline stage"), std::string::npos) << why;
}

}  // namespace
}  // namespace echosim::gpu
