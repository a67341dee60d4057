#pragma once
// A minimal frame graph. Passes declare the images they read and write; compile() culls every
// pass whose writes nobody downstream reads (unless it has side effects such as presenting),
// and execute() records the live passes in order with the barriers their declared uses need,
// timing each pass on the CPU and, where the device supports it, on the GPU.
#include <functional>
#include <string>
#include <vector>

#include <weft/FrameStats.h>

#include "vk/Resources.h"

namespace weft::render {

enum class Use {
    ColorWrite,    // colour attachment
    DepthWrite,    // depth attachment (read + write), kept for later passes (store op STORE)
    DepthScratch,  // depth attachment the pass does not keep (store op DONT_CARE): no later
                   // pass may sample or copy it until another pass writes it
    Sampled,       // sampled/fetched in a fragment shader
    TransferRead,  // copy source (readback)
    TransferWrite, // copy destination
    Present,       // handed to the presentation engine after the frame
};

struct ResourceUse {
    int resource;
    Use use;
};

struct Pass {
    std::string name;
    std::vector<ResourceUse> reads;
    std::vector<ResourceUse> writes;
    std::function<void(VkCommandBuffer)> record;
    bool sideEffect = false; // live even if nobody reads its writes (e.g. readback copies)
};

class Timestamps;

class FrameGraph {
public:
    /// Registers an image (may be null in tests that only compile()).
    int addResource(const std::string& name, vk::Image* image);
    void addPass(Pass pass);
    /// Resources the frame must produce (read back, presented).
    void markOutput(int resource);

    /// Indices of live passes in submission order; also fills culledPasses(). Throws
    /// weft::Error when a live pass samples or copies a depth a DepthScratch pass discarded.
    std::vector<int> compile();
    const std::vector<std::string>& culledPasses() const { return mCulled; }
    const std::vector<Pass>& passes() const { return mPasses; }

    /// Records the live passes with barriers derived from their declared uses.
    void execute(vk::Context& ctx, VkCommandBuffer cmd, Timestamps* timestamps, FrameStats& stats);

private:
    struct Resource {
        std::string name;
        vk::Image* image;
    };
    std::vector<Resource> mResources;
    std::vector<Pass> mPasses;
    std::vector<int> mOutputs;
    std::vector<std::string> mCulled;
};

/// Layout, pipeline stage and access an image needs for a use.
struct UseState {
    VkImageLayout layout;
    VkPipelineStageFlags2 stage;
    VkAccessFlags2 access;
};
UseState useState(Use use, bool depth);

/// GPU timestamps: a begin/end pair per pass, read back after the frame's submission finished.
class Timestamps {
public:
    Timestamps(vk::Context& ctx, uint32_t maxPasses);
    bool supported() const { return mPeriodNs > 0; }
    void reset(VkCommandBuffer cmd);
    /// Returns the query pair index of the pass, or -1 when out of queries / unsupported.
    int begin(VkCommandBuffer cmd);
    void end(VkCommandBuffer cmd, int index);
    /// Milliseconds of pair `index` of the last completed use, negative if unavailable.
    std::vector<double> read(uint32_t count);
    uint32_t used() const { return mUsed; }

private:
    vk::Context& mCtx;
    vk::QueryPool mPool;
    uint32_t mMax;
    uint32_t mUsed = 0;
    double mPeriodNs;
};

} // namespace weft::render
