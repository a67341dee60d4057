#include "render/CoatAlbedoGpu.h"

#include <vector>

#include <weft/IblFilter.h>

#include "render/FrameGraph.h"
#include "render/GpuTypes.h"

namespace weft::render {

vk::Image uploadCoatAlbedo(vk::Context& ctx) {
    static const std::vector<float> table =
        coatAlbedoTable(gpu::COAT_COSINES, gpu::COAT_ROUGHNESS, gpu::COAT_F0);
    vk::ImageDesc d;
    d.width = uint32_t(gpu::COAT_COSINES);
    d.height = uint32_t(gpu::COAT_ROUGHNESS);
    d.layers = uint32_t(gpu::COAT_F0);
    d.format = VK_FORMAT_R32_SFLOAT;
    d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    vk::Image image(&ctx, d);
    const VkDeviceSize bytes = table.size() * sizeof(float);
    vk::Buffer staging(&ctx, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, vk::MemoryUsage::Upload);
    staging.write(table.data(), bytes);
    ctx.immediate([&](VkCommandBuffer cmd) {
        vk::transition(ctx, cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                       VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, d.layers};
        region.imageExtent = {d.width, d.height, 1};
        vkCmdCopyBufferToImage(cmd, staging.get(), image.get(),
                               VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
        const UseState s = useState(Use::Sampled, false);
        vk::transition(ctx, cmd, image, s.layout, s.stage, s.access);
    });
    return image;
}

} // namespace weft::render
