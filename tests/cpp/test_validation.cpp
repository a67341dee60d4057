// The validation layers as the tests run them (WEFT_VALIDATION=1): synchronization validation is
// on, so a missing barrier is reported on lavapipe too, which runs every command in order and
// would otherwise show such a bug only on a GPU.
#include <gtest/gtest.h>

#include <weft/Device.h>

#include "vk/Context.h"
#include "vk/Resources.h"

namespace {

TEST(Validation, ReportsAMissingBarrier) {
    if (!weft::validationEnabled()) GTEST_SKIP() << "WEFT_VALIDATION is not set";
    auto ctx = weft::vk::Context::shared();
    weft::vk::Buffer a(ctx.get(), 256, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                       weft::vk::MemoryUsage::Upload);
    weft::vk::Buffer b(ctx.get(), 256, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                       weft::vk::MemoryUsage::GpuOnly);
    weft::clearValidationMessages();
    ctx->immediate([&](VkCommandBuffer cmd) { // two writes of one range, nothing between them
        const VkBufferCopy region{0, 0, 256};
        vkCmdCopyBuffer(cmd, a.get(), b.get(), 1, &region);
        vkCmdCopyBuffer(cmd, a.get(), b.get(), 1, &region);
    });
    const std::vector<std::string> messages = weft::validationMessages();
    weft::clearValidationMessages();
    ASSERT_FALSE(messages.empty());
    EXPECT_NE(messages[0].find("WRITE_AFTER_WRITE"), std::string::npos) << messages[0];
}

} // namespace
