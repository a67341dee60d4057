#include "vk/Resources.h"

#include <cstring>
#include <string>

#include <glm/gtc/packing.hpp>

#include "vk/EmbeddedShaders.h"
#include "vk/ShaderSource.h"

namespace weft::vk {

Buffer::Buffer(Context* ctx, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUsage memory)
    : mCtx(ctx), mSize(size) {
    if (size == 0) throw Error("Buffer: size must be > 0");
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = size;
    info.usage = usage;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    VK_CHECK(vkCreateBuffer(ctx->device(), &info, nullptr, &mBuffer));
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(ctx->device(), mBuffer, &req);
    try {
        mAlloc = ctx->allocator().allocate(req, memory, true);
    } catch (...) {
        vkDestroyBuffer(ctx->device(), mBuffer, nullptr);
        mBuffer = VK_NULL_HANDLE;
        throw;
    }
    VK_CHECK(vkBindBufferMemory(ctx->device(), mBuffer, mAlloc.memory, mAlloc.offset));
}

Buffer& Buffer::operator=(Buffer&& o) noexcept {
    if (this != &o) {
        reset();
        mCtx = o.mCtx;
        mBuffer = std::exchange(o.mBuffer, VkBuffer(VK_NULL_HANDLE));
        mSize = o.mSize;
        mAlloc = std::exchange(o.mAlloc, Allocation{});
    }
    return *this;
}

void Buffer::write(const void* data, VkDeviceSize bytes, VkDeviceSize offset) {
    if (!mAlloc.mapped) throw Error("Buffer::write on a buffer that is not host-visible");
    if (offset + bytes > mSize) throw Error("Buffer::write past the end of the buffer");
    std::memcpy(static_cast<char*>(mAlloc.mapped) + offset, data, bytes);
}

void Buffer::reset() {
    if (mBuffer == VK_NULL_HANDLE) return;
    Context* ctx = mCtx;
    VkBuffer b = std::exchange(mBuffer, VkBuffer(VK_NULL_HANDLE));
    Allocation a = std::exchange(mAlloc, Allocation{});
    ctx->retire([ctx, b, a] {
        vkDestroyBuffer(ctx->device(), b, nullptr);
        ctx->allocator().free(a);
    });
}

bool isDepthFormat(VkFormat f) {
    return f == VK_FORMAT_D32_SFLOAT || f == VK_FORMAT_D16_UNORM ||
           f == VK_FORMAT_D24_UNORM_S8_UINT || f == VK_FORMAT_D32_SFLOAT_S8_UINT ||
           f == VK_FORMAT_X8_D24_UNORM_PACK32;
}

uint32_t formatBytes(VkFormat f) {
    switch (f) {
    case VK_FORMAT_R8G8B8A8_UNORM:
    case VK_FORMAT_R8G8B8A8_SRGB:
    case VK_FORMAT_B8G8R8A8_UNORM:
    case VK_FORMAT_B8G8R8A8_SRGB:
    case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_R32_SFLOAT: return 4;
    case VK_FORMAT_R16G16B16A16_SFLOAT: return 8;
    case VK_FORMAT_R32G32B32A32_SFLOAT: return 16;
    default: throw Error("formatBytes: unsupported format " + std::to_string(int(f)));
    }
}

std::vector<float> readFloats(const void* mapped, size_t count, VkFormat format) {
    std::vector<float> v(count);
    if (format == VK_FORMAT_R32G32B32A32_SFLOAT) {
        std::memcpy(v.data(), mapped, count * sizeof(float));
    } else if (format == VK_FORMAT_R16G16B16A16_SFLOAT) {
        const auto* h = static_cast<const uint16_t*>(mapped);
        for (size_t i = 0; i < count; ++i) v[i] = glm::unpackHalf1x16(h[i]);
    } else {
        throw Error("readFloats: not a float format: " + std::to_string(int(format)));
    }
    return v;
}

Image::Image(Context* ctx, const ImageDesc& desc) : mCtx(ctx), mDesc(desc) {
    if (desc.width == 0 || desc.height == 0 || desc.layers == 0 || desc.mipLevels == 0)
        throw InvalidArgument("image size must be at least 1x1 (got " + std::to_string(desc.width) +
                              "x" + std::to_string(desc.height) + ")");
    const auto& limits = ctx->properties().limits;
    if (desc.width > limits.maxImageDimension2D || desc.height > limits.maxImageDimension2D)
        throw InvalidArgument("image size " + std::to_string(desc.width) + "x" +
                              std::to_string(desc.height) + " exceeds the device limit " +
                              std::to_string(limits.maxImageDimension2D));
    mAspect = isDepthFormat(desc.format) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    if (desc.cube && desc.layers != 6) throw InvalidArgument("a cube image has 6 layers");
    info.flags = desc.cube ? VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT : 0;
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = desc.format;
    info.extent = {desc.width, desc.height, 1};
    info.mipLevels = desc.mipLevels;
    info.arrayLayers = desc.layers;
    info.samples = desc.samples;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = desc.usage;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VK_CHECK(vkCreateImage(ctx->device(), &info, nullptr, &mImage));
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(ctx->device(), mImage, &req);
    try {
        mAlloc = ctx->allocator().allocate(req, MemoryUsage::GpuOnly, false);
        VK_CHECK(vkBindImageMemory(ctx->device(), mImage, mAlloc.memory, mAlloc.offset));
        auto makeView = [&](VkImageViewType type, uint32_t baseLayer, uint32_t layers) {
            VkImageViewCreateInfo v{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
            v.image = mImage;
            v.viewType = type;
            v.format = desc.format;
            v.subresourceRange = {mAspect, 0, desc.mipLevels, baseLayer, layers};
            VkImageView view;
            VK_CHECK(vkCreateImageView(ctx->device(), &v, nullptr, &view));
            return view;
        };
        mView = makeView(desc.cube ? VK_IMAGE_VIEW_TYPE_CUBE
                         : desc.layers > 1 || (desc.usage & VK_IMAGE_USAGE_SAMPLED_BIT &&
                                               isDepthFormat(desc.format))
                             ? VK_IMAGE_VIEW_TYPE_2D_ARRAY
                             : VK_IMAGE_VIEW_TYPE_2D,
                         0, desc.layers);
        if (desc.layers > 1 || isDepthFormat(desc.format))
            for (uint32_t l = 0; l < desc.layers; ++l)
                mLayerViews.push_back(makeView(VK_IMAGE_VIEW_TYPE_2D, l, 1));
        else
            mLayerViews.push_back(mView);
    } catch (...) {
        reset();
        throw;
    }
}

Image Image::external(VkImage image, VkImageView view, const ImageDesc& desc) {
    Image i;
    i.mOwned = false;
    i.mImage = image;
    i.mView = view;
    i.mLayerViews = {view};
    i.mDesc = desc;
    i.mAspect = isDepthFormat(desc.format) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
    return i;
}

Image& Image::operator=(Image&& o) noexcept {
    if (this != &o) {
        reset();
        mCtx = o.mCtx;
        mOwned = o.mOwned;
        mImage = std::exchange(o.mImage, VkImage(VK_NULL_HANDLE));
        mView = std::exchange(o.mView, VkImageView(VK_NULL_HANDLE));
        mLayerViews = std::move(o.mLayerViews);
        o.mLayerViews.clear();
        mDesc = o.mDesc;
        mAspect = o.mAspect;
        mAlloc = std::exchange(o.mAlloc, Allocation{});
        layout = o.layout;
        stage = o.stage;
        access = o.access;
    }
    return *this;
}

void Image::reset() {
    if (mImage == VK_NULL_HANDLE) return;
    if (!mOwned) {
        mImage = VK_NULL_HANDLE;
        mView = VK_NULL_HANDLE;
        mLayerViews.clear();
        return;
    }
    Context* ctx = mCtx;
    VkImage image = std::exchange(mImage, VkImage(VK_NULL_HANDLE));
    std::vector<VkImageView> views = std::move(mLayerViews);
    mLayerViews.clear();
    if (views.empty() || views[0] != mView) views.push_back(mView);
    mView = VK_NULL_HANDLE;
    Allocation a = std::exchange(mAlloc, Allocation{});
    layout = VK_IMAGE_LAYOUT_UNDEFINED;
    ctx->retire([ctx, image, views, a] {
        for (VkImageView v : views)
            if (v) vkDestroyImageView(ctx->device(), v, nullptr);
        vkDestroyImage(ctx->device(), image, nullptr);
        ctx->allocator().free(a);
    });
}

void uploadBuffer(Context& ctx, const Buffer& dst, const void* data, VkDeviceSize bytes) {
    Buffer staging(&ctx, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::Upload);
    staging.write(data, bytes);
    ctx.immediate([&](VkCommandBuffer cmd) {
        const VkBufferCopy region{0, 0, bytes};
        vkCmdCopyBuffer(cmd, staging.get(), dst.get(), 1, &region);
        // The fence the upload waits on makes the copy's writes available, not visible: later
        // submissions read them only after a memory dependency such as this one.
        VkMemoryBarrier2 b{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
        b.srcStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
        b.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
        b.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
        b.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT;
        VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
        dep.memoryBarrierCount = 1;
        dep.pMemoryBarriers = &b;
        ctx.fn().cmdPipelineBarrier2(cmd, &dep);
    });
}

void transition(Context& ctx, VkCommandBuffer cmd, Image& image, VkImageLayout layout,
                VkPipelineStageFlags2 stage, VkAccessFlags2 access) {
    VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    b.srcStageMask =
        image.stage == VK_PIPELINE_STAGE_2_NONE ? VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT : image.stage;
    b.srcAccessMask = image.access;
    b.dstStageMask = stage;
    b.dstAccessMask = access;
    b.oldLayout = image.layout;
    b.newLayout = layout;
    b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image.get();
    b.subresourceRange = {image.aspect(), 0, image.desc().mipLevels, 0, image.desc().layers};
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.imageMemoryBarrierCount = 1;
    dep.pImageMemoryBarriers = &b;
    ctx.fn().cmdPipelineBarrier2(cmd, &dep);
    image.layout = layout;
    image.stage = stage;
    image.access = access;
}

ShaderModule createShaderModule(Context& ctx, const char* name) {
    const std::vector<uint32_t> words = shaderWords(name); // hot-reloaded or embedded
    VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    info.codeSize = words.size() * sizeof(uint32_t);
    info.pCode = words.data();
    VkShaderModule module;
    VK_CHECK(vkCreateShaderModule(ctx.device(), &info, nullptr, &module));
    return ShaderModule(&ctx, module, vkDestroyShaderModule);
}

} // namespace weft::vk
