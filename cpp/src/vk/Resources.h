#pragma once
// RAII wrappers for Vulkan objects. Destruction is deferred through Context::retire, so a
// wrapper may be dropped while the GPU still uses the object in a frame in flight.
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "vk/Context.h"

namespace weft::vk {

/// Owns one Vulkan handle of a device-level type; destroyed after in-flight work completes.
template <typename T> class Handle {
public:
    using Destroy = void (*)(VkDevice, T, const VkAllocationCallbacks*);
    Handle() = default;
    Handle(Context* ctx, T handle, Destroy destroy)
        : mCtx(ctx), mHandle(handle), mDestroy(destroy) {}
    ~Handle() { reset(); }
    Handle(Handle&& o) noexcept { *this = std::move(o); }
    Handle& operator=(Handle&& o) noexcept {
        if (this != &o) {
            reset();
            mCtx = o.mCtx;
            mHandle = std::exchange(o.mHandle, T(VK_NULL_HANDLE));
            mDestroy = o.mDestroy;
        }
        return *this;
    }
    Handle(const Handle&) = delete;
    Handle& operator=(const Handle&) = delete;

    T get() const { return mHandle; }
    operator T() const { return mHandle; }
    explicit operator bool() const { return mHandle != VK_NULL_HANDLE; }
    void reset() {
        if (mHandle == VK_NULL_HANDLE) return;
        Context* ctx = mCtx;
        T h = std::exchange(mHandle, T(VK_NULL_HANDLE));
        Destroy d = mDestroy;
        ctx->retire([ctx, h, d] { d(ctx->device(), h, nullptr); });
    }

private:
    Context* mCtx = nullptr;
    T mHandle = VK_NULL_HANDLE;
    Destroy mDestroy = nullptr;
};

using Pipeline = Handle<VkPipeline>;
using PipelineLayout = Handle<VkPipelineLayout>;
using DescriptorSetLayout = Handle<VkDescriptorSetLayout>;
using DescriptorPool = Handle<VkDescriptorPool>;
using Sampler = Handle<VkSampler>;
using ShaderModule = Handle<VkShaderModule>;
using Semaphore = Handle<VkSemaphore>;
using QueryPool = Handle<VkQueryPool>;
using ImageView = Handle<VkImageView>;
using CommandPool = Handle<VkCommandPool>;

class Buffer {
public:
    Buffer() = default;
    Buffer(Context* ctx, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUsage memory);
    ~Buffer() { reset(); }
    Buffer(Buffer&& o) noexcept { *this = std::move(o); }
    Buffer& operator=(Buffer&& o) noexcept;
    Buffer(const Buffer&) = delete;
    Buffer& operator=(const Buffer&) = delete;

    VkBuffer get() const { return mBuffer; }
    VkDeviceSize size() const { return mSize; }
    void* mapped() const { return mAlloc.mapped; }
    explicit operator bool() const { return mBuffer != VK_NULL_HANDLE; }
    /// Copies `bytes` into a host-visible buffer at `offset`.
    void write(const void* data, VkDeviceSize bytes, VkDeviceSize offset = 0);
    void reset();

private:
    Context* mCtx = nullptr;
    VkBuffer mBuffer = VK_NULL_HANDLE;
    VkDeviceSize mSize = 0;
    Allocation mAlloc;
};

struct ImageDesc {
    uint32_t width = 1, height = 1, layers = 1, mipLevels = 1;
    VkFormat format = VK_FORMAT_R8G8B8A8_UNORM;
    VkImageUsageFlags usage = 0;
    bool cube = false; // 6 layers viewed as a cube map (view() is VK_IMAGE_VIEW_TYPE_CUBE)
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT; // > 1: a multisampled render target
};

/// A 2D (array) image with one view over all layers and mips, and per-layer views for
/// rendering into single layers. The layout and last access are tracked for barriers.
class Image {
public:
    Image() = default;
    Image(Context* ctx, const ImageDesc& desc);
    /// Wraps an image owned elsewhere (a swapchain image): state is tracked, nothing destroyed.
    static Image external(VkImage image, VkImageView view, const ImageDesc& desc);
    ~Image() { reset(); }
    Image(Image&& o) noexcept { *this = std::move(o); }
    Image& operator=(Image&& o) noexcept;
    Image(const Image&) = delete;
    Image& operator=(const Image&) = delete;

    VkImage get() const { return mImage; }
    VkImageView view() const { return mView; }
    VkImageView layerView(uint32_t layer) const { return mLayerViews.at(layer); }
    const ImageDesc& desc() const { return mDesc; }
    VkImageAspectFlags aspect() const { return mAspect; }
    explicit operator bool() const { return mImage != VK_NULL_HANDLE; }
    void reset();

    // Tracked state (whole image), updated by whoever records a barrier.
    VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkPipelineStageFlags2 stage = VK_PIPELINE_STAGE_2_NONE;
    VkAccessFlags2 access = VK_ACCESS_2_NONE;

private:
    Context* mCtx = nullptr;
    bool mOwned = true;
    VkImage mImage = VK_NULL_HANDLE;
    VkImageView mView = VK_NULL_HANDLE;
    std::vector<VkImageView> mLayerViews;
    ImageDesc mDesc;
    VkImageAspectFlags mAspect = VK_IMAGE_ASPECT_COLOR_BIT;
    Allocation mAlloc;
};

bool isDepthFormat(VkFormat format);
/// Bytes per texel of the uncompressed formats weft uses.
uint32_t formatBytes(VkFormat format);
/// `count` values of a read-back RGBA32F or RGBA16F image as floats (weft::Error otherwise).
std::vector<float> readFloats(const void* mapped, size_t count, VkFormat format);

/// Copies `bytes` of host data into the device-local buffer `dst` through a staging buffer and
/// waits; the copy is made visible to every later use of `dst` (vertices, indices, storage).
void uploadBuffer(Context& ctx, const Buffer& dst, const void* data, VkDeviceSize bytes);

/// Records a full-image layout transition (sync2), updating the image's tracked state.
void transition(Context& ctx, VkCommandBuffer cmd, Image& image, VkImageLayout layout,
                VkPipelineStageFlags2 stage, VkAccessFlags2 access);

/// Creates a shader module from embedded SPIR-V by name (path relative to glsl/).
ShaderModule createShaderModule(Context& ctx, const char* name);

} // namespace weft::vk
