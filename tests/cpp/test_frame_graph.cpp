#include <gtest/gtest.h>

#include "render/FrameGraph.h"

using namespace weft::render;

namespace {
std::vector<std::string> names(const FrameGraph& g, const std::vector<int>& order) {
    std::vector<std::string> out;
    for (int i : order) out.push_back(g.passes()[size_t(i)].name);
    return out;
}
} // namespace

TEST(FrameGraph, CullsPassesNobodyReads) {
    FrameGraph g;
    int shadow = g.addResource("shadow", nullptr);
    int hdr = g.addResource("hdr", nullptr);
    int ldr = g.addResource("ldr", nullptr);
    auto noop = [](VkCommandBuffer) {};
    g.addPass({"shadow", {}, {{shadow, Use::DepthWrite}}, noop});
    g.addPass({"forward", {{shadow, Use::Sampled}}, {{hdr, Use::ColorWrite}}, noop});
    g.addPass({"output", {{hdr, Use::Sampled}}, {{ldr, Use::ColorWrite}}, noop});
    g.addPass({"readback", {{hdr, Use::TransferRead}}, {}, noop, true});
    // Only linear radiance is read back: the sRGB output pass has no reader.
    EXPECT_EQ(names(g, g.compile()), (std::vector<std::string>{"shadow", "forward", "readback"}));
    EXPECT_EQ(g.culledPasses(), std::vector<std::string>{"output"});
}

TEST(FrameGraph, OutputsKeepTheirProducers) {
    FrameGraph g;
    int a = g.addResource("a", nullptr);
    int b = g.addResource("b", nullptr);
    auto noop = [](VkCommandBuffer) {};
    g.addPass({"makeA", {}, {{a, Use::ColorWrite}}, noop});
    g.addPass({"makeB", {{a, Use::Sampled}}, {{b, Use::ColorWrite}}, noop});
    EXPECT_TRUE(g.compile().empty()); // nothing is an output, nothing has side effects
    g.markOutput(b);
    EXPECT_EQ(names(g, g.compile()), (std::vector<std::string>{"makeA", "makeB"}));
}

TEST(FrameGraph, RejectsUnknownResources) {
    FrameGraph g;
    EXPECT_THROW(g.addPass({"bad", {{3, Use::Sampled}}, {}, [](VkCommandBuffer) {}}), weft::Error);
}

// A depth a pass does not store (DONT_CARE) is undefined afterwards: lavapipe keeps it, a GPU
// need not, so the graph refuses a later read.
TEST(FrameGraph, RejectsReadingADiscardedDepth) {
    FrameGraph g;
    const int depth = g.addResource("depth", nullptr);
    const int out = g.addResource("out", nullptr);
    g.addPass({"capture", {}, {{depth, Use::DepthScratch}}, [](VkCommandBuffer) {}});
    g.addPass(
        {"project", {{depth, Use::Sampled}}, {{out, Use::ColorWrite}}, [](VkCommandBuffer) {}});
    g.markOutput(out);
    EXPECT_THROW(g.compile(), weft::Error);
}

TEST(FrameGraph, AcceptsADiscardedDepthWrittenAgainBeforeItIsRead) {
    FrameGraph g;
    const int depth = g.addResource("depth", nullptr);
    const int out = g.addResource("out", nullptr);
    g.addPass({"scratch", {}, {{depth, Use::DepthScratch}}, [](VkCommandBuffer) {}});
    g.addPass({"kept", {}, {{depth, Use::DepthWrite}}, [](VkCommandBuffer) {}});
    g.addPass(
        {"project", {{depth, Use::Sampled}}, {{out, Use::ColorWrite}}, [](VkCommandBuffer) {}});
    g.markOutput(out);
    EXPECT_EQ(g.compile().size(), 3u);
    EXPECT_EQ(useState(Use::DepthScratch, true).layout, useState(Use::DepthWrite, true).layout);
}

TEST(FrameGraph, UseStatesMatchVulkanLayouts) {
    EXPECT_EQ(useState(Use::Sampled, true).layout, VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL);
    EXPECT_EQ(useState(Use::Sampled, false).layout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    EXPECT_EQ(useState(Use::TransferRead, false).layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    EXPECT_EQ(useState(Use::Present, false).layout, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);
}
