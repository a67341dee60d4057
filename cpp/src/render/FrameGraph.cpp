#include "render/FrameGraph.h"

#include <algorithm>
#include <chrono>
#include <set>

namespace weft::render {

int FrameGraph::addResource(const std::string& name, vk::Image* image) {
    mResources.push_back({name, image});
    return int(mResources.size() - 1);
}

void FrameGraph::addPass(Pass pass) {
    for (const auto* uses : {&pass.reads, &pass.writes})
        for (const ResourceUse& u : *uses)
            if (u.resource < 0 || u.resource >= int(mResources.size()))
                throw Error("frame graph: pass '" + pass.name + "' uses an unknown resource");
    mPasses.push_back(std::move(pass));
}

void FrameGraph::markOutput(int resource) { mOutputs.push_back(resource); }

std::vector<int> FrameGraph::compile() {
    // Walk backwards: a pass lives if it has side effects or writes something still needed;
    // a live pass makes everything it reads needed by the passes before it.
    std::set<int> needed(mOutputs.begin(), mOutputs.end());
    std::vector<bool> live(mPasses.size(), false);
    for (int i = int(mPasses.size()) - 1; i >= 0; --i) {
        const Pass& p = mPasses[size_t(i)];
        bool writesNeeded = false;
        for (const ResourceUse& w : p.writes) writesNeeded |= needed.count(w.resource) > 0;
        if (!(p.sideEffect || writesNeeded)) continue;
        live[size_t(i)] = true;
        for (const ResourceUse& r : p.reads) needed.insert(r.resource);
    }
    std::vector<int> order;
    mCulled.clear();
    // Which pass left each resource discarded (DepthScratch): its contents are undefined after
    // it (store op DONT_CARE). lavapipe keeps them anyway, a GPU need not, so reading them is
    // caught here rather than on a GPU.
    std::vector<const Pass*> discardedBy(mResources.size(), nullptr);
    for (size_t i = 0; i < mPasses.size(); ++i) {
        if (!live[i]) {
            mCulled.push_back(mPasses[i].name);
            continue;
        }
        order.push_back(int(i));
        const Pass& p = mPasses[i];
        for (const ResourceUse& r : p.reads)
            if (const Pass* by = discardedBy[size_t(r.resource)])
                throw Error("frame graph: pass '" + p.name + "' reads '" +
                            mResources[size_t(r.resource)].name + "', which pass '" + by->name +
                            "' did not keep (Use::DepthScratch)");
        for (const ResourceUse& w : p.writes)
            discardedBy[size_t(w.resource)] = w.use == Use::DepthScratch ? &p : nullptr;
    }
    return order;
}

UseState useState(Use use, bool depth) {
    switch (use) {
    case Use::ColorWrite:
        return {VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT};
    case Use::DepthWrite:
    case Use::DepthScratch:
        // A multisample resolve into a depth attachment runs in the colour-output stage as a
        // colour-attachment write (Vulkan spec, "Render Pass Operations"), hence those too.
        return {VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT |
                    VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT |
                    VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
                    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
                    VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT};
    case Use::Sampled:
        return {depth ? VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL
                      : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT};
    case Use::TransferRead:
        return {VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT,
                VK_ACCESS_2_TRANSFER_READ_BIT};
    case Use::TransferWrite:
        return {VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT,
                VK_ACCESS_2_TRANSFER_WRITE_BIT};
    case Use::Present:
        return {VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE};
    }
    throw Error("frame graph: unknown use");
}

void FrameGraph::execute(vk::Context& ctx, VkCommandBuffer cmd, Timestamps* timestamps,
                         FrameStats& stats) {
    using Clock = std::chrono::steady_clock;
    const std::vector<int> order = compile();
    stats.passes.clear();
    stats.culled = mCulled;
    for (int index : order) {
        Pass& p = mPasses[size_t(index)];
        const auto t0 = Clock::now();
        // Barriers: every declared use moves its image into the state the use needs. A pass
        // that both reads and writes one image (not used here) would keep the write state.
        for (const auto* uses : {&p.reads, &p.writes}) {
            for (const ResourceUse& u : *uses) {
                vk::Image* image = mResources[size_t(u.resource)].image;
                if (!image) continue;
                const UseState s = useState(u.use, vk::isDepthFormat(image->desc().format));
                const bool sameReadState = image->layout == s.layout &&
                                           (u.use == Use::Sampled || u.use == Use::TransferRead) &&
                                           image->access == s.access;
                if (!sameReadState) vk::transition(ctx, cmd, *image, s.layout, s.stage, s.access);
            }
        }
        const int query = timestamps ? timestamps->begin(cmd) : -1;
        p.record(cmd);
        if (timestamps) timestamps->end(cmd, query);
        PassStats ps;
        ps.name = p.name;
        ps.cpuMs = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
        stats.passes.push_back(ps);
    }
}

Timestamps::Timestamps(vk::Context& ctx, uint32_t maxPasses)
    : mCtx(ctx), mMax(maxPasses), mPeriodNs(ctx.timestampPeriodNs()) {
    if (!supported()) return;
    VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    info.queryType = VK_QUERY_TYPE_TIMESTAMP;
    info.queryCount = 2 * maxPasses;
    VkQueryPool pool;
    VK_CHECK(vkCreateQueryPool(ctx.device(), &info, nullptr, &pool));
    mPool = vk::QueryPool(&ctx, pool, vkDestroyQueryPool);
}

void Timestamps::reset(VkCommandBuffer cmd) {
    mUsed = 0;
    if (supported()) vkCmdResetQueryPool(cmd, mPool, 0, 2 * mMax);
}

int Timestamps::begin(VkCommandBuffer cmd) {
    if (!supported() || mUsed >= mMax) return -1;
    const int index = int(mUsed++);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, mPool, uint32_t(2 * index));
    return index;
}

void Timestamps::end(VkCommandBuffer cmd, int index) {
    if (index < 0) return;
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, mPool, uint32_t(2 * index + 1));
}

std::vector<double> Timestamps::read(uint32_t count) {
    std::vector<double> ms(count, -1.0);
    if (!supported() || count == 0) return ms;
    count = std::min(count, mUsed);
    std::vector<uint64_t> ticks(2 * size_t(count) * 2, 0); // value + availability per query
    VkResult r = vkGetQueryPoolResults(
        mCtx.device(), mPool, 0, 2 * count, ticks.size() * sizeof(uint64_t), ticks.data(),
        2 * sizeof(uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WITH_AVAILABILITY_BIT);
    if (r != VK_SUCCESS && r != VK_NOT_READY) VK_CHECK(r);
    for (uint32_t i = 0; i < count; ++i) {
        const uint64_t b = ticks[4 * i], bAvail = ticks[4 * i + 1];
        const uint64_t e = ticks[4 * i + 2], eAvail = ticks[4 * i + 3];
        if (bAvail && eAvail && e >= b) ms[i] = double(e - b) * mPeriodNs * 1e-6;
    }
    return ms;
}

} // namespace weft::render
