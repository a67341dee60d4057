#include "ImGuiLayer.h"

#include <cmath>

#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>
#include <imgui.h>

#include "render/FrameGraph.h"
#include "render/FramePasses.h"
#include "render/RenderTargets.h"
#include "vk/Context.h"
#include "vk/WindowNative.h"

namespace weft::demo {
namespace {

void checkVk(VkResult result) {
    if (result < 0) vk::throwVkError(result, "ImGui's Vulkan backend", __FILE__, __LINE__);
}

bool isSrgb(VkFormat format) {
    return format == VK_FORMAT_B8G8R8A8_SRGB || format == VK_FORMAT_R8G8B8A8_SRGB ||
           format == VK_FORMAT_A8B8G8R8_SRGB_PACK32;
}

// ImGui's colours are sRGB values meant to be written as they are. An *_SRGB swapchain encodes
// what the shader writes, so the style is decoded to linear first (IEC 61966-2-1) or every
// colour would show too light.
void linearizeStyle(ImGuiStyle& style) {
    auto decode = [](float c) {
        return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
    };
    for (ImVec4& c : style.Colors) c = ImVec4(decode(c.x), decode(c.y), decode(c.z), c.w);
}

} // namespace

ImGuiLayer::ImGuiLayer(Window& window, Renderer& renderer)
    : mWindow(window), mRenderer(renderer), mCtx(*vk::WindowAccess::native(window).ctx),
      mFormat(vk::WindowAccess::native(window).format) {
    VkDevice device = mCtx.device();
    // Draws over the tone-mapped image: loads it and leaves it where the frame graph expects a
    // colour attachment (the graph's barriers move it on to readback or presentation).
    VkAttachmentDescription color{};
    color.format = mFormat;
    color.samples = VK_SAMPLE_COUNT_1_BIT;
    color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    color.initialLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    color.finalLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &ref;
    VkRenderPassCreateInfo rp{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    rp.attachmentCount = 1;
    rp.pAttachments = &color;
    rp.subpassCount = 1;
    rp.pSubpasses = &subpass;
    VK_CHECK(vkCreateRenderPass(device, &rp, nullptr, &mRenderPass));

    // The backend's one descriptor set: the font atlas.
    VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1};
    VkDescriptorPoolCreateInfo pool{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pool.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
    pool.maxSets = 1;
    pool.poolSizeCount = 1;
    pool.pPoolSizes = &size;
    VK_CHECK(vkCreateDescriptorPool(device, &pool, nullptr, &mPool));

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr; // no imgui.ini left in the working directory
    ImGui::StyleColorsDark();
    if (isSrgb(mFormat)) linearizeStyle(ImGui::GetStyle());
    // Chains the window's own GLFW callbacks (set when it was made), so the demo keeps its input.
    ImGui_ImplGlfw_InitForVulkan(vk::WindowAccess::native(window).window, true);
    ImGui_ImplVulkan_InitInfo info{};
    info.Instance = mCtx.instance();
    info.PhysicalDevice = mCtx.physicalDevice();
    info.Device = device;
    info.QueueFamily = mCtx.queueFamily();
    info.Queue = mCtx.queue();
    info.DescriptorPool = mPool;
    // Vertex buffers are cycled over ImageCount frames: more than the renderer's frames in
    // flight, so none is rewritten while the GPU may still read it.
    info.MinImageCount = 2;
    info.ImageCount = 3;
    info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
    info.CheckVkResultFn = checkVk;
    ImGui_ImplVulkan_Init(&info, mRenderPass);
    mCtx.immediate([](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
    ImGui_ImplVulkan_DestroyFontUploadObjects();
    render::setFrameOverlay(mRenderer, this);
}

ImGuiLayer::~ImGuiLayer() {
    render::setFrameOverlay(mRenderer, nullptr);
    // Every frame that drew with the backend's buffers and pipeline has finished.
    mCtx.waitFor(mCtx.lastSubmitted());
    ImGui_ImplVulkan_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    VkDevice device = mCtx.device();
    for (auto& [view, fb] : mFramebuffers) vkDestroyFramebuffer(device, fb, nullptr);
    vkDestroyDescriptorPool(device, mPool, nullptr);
    vkDestroyRenderPass(device, mRenderPass, nullptr);
}

void ImGuiLayer::beginFrame() {
    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
}

void ImGuiLayer::endFrame(bool draw) {
    ImGui::Render();
    mDraw = draw;
}

void ImGuiLayer::dropFramebuffers() {
    // Frames already submitted may still use them: destroyed once those finished.
    VkDevice device = mCtx.device();
    for (auto& [view, fb] : mFramebuffers)
        mCtx.retire([device, fb = fb] { vkDestroyFramebuffer(device, fb, nullptr); });
    mFramebuffers.clear();
}

VkFramebuffer ImGuiLayer::framebuffer(VkImageView view, uint32_t width, uint32_t height) {
    if (vk::WindowAccess::native(mWindow).swapchain != mSwapchain) {
        dropFramebuffers();
        mSwapchain = vk::WindowAccess::native(mWindow).swapchain;
    }
    if (auto it = mFramebuffers.find(view); it != mFramebuffers.end()) return it->second;
    VkFramebufferCreateInfo info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    info.renderPass = mRenderPass;
    info.attachmentCount = 1;
    info.pAttachments = &view;
    info.width = width;
    info.height = height;
    info.layers = 1;
    VkFramebuffer fb;
    VK_CHECK(vkCreateFramebuffer(mCtx.device(), &info, nullptr, &fb));
    return mFramebuffers[view] = fb;
}

void ImGuiLayer::addPasses(render::FrameGraph& g, render::FramePassContext& f) {
    ImDrawData* data = ImGui::GetDrawData();
    // Nothing to draw, or a swapchain whose format the pipeline was not made for.
    if (!mDraw || !data || data->CmdListsCount == 0 || f.ldr->desc().format != mFormat) return;
    const uint32_t w = f.targets.width, h = f.targets.height;
    const VkFramebuffer fb = framebuffer(f.ldr->view(), w, h);
    g.addPass({"panel",
               {},
               {{f.rLdr, render::Use::ColorWrite}},
               [this, fb, w, h, data](VkCommandBuffer cmd) {
                   VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
                   begin.renderPass = mRenderPass;
                   begin.framebuffer = fb;
                   begin.renderArea = {{0, 0}, {w, h}};
                   vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
                   ImGui_ImplVulkan_RenderDrawData(data, cmd);
                   vkCmdEndRenderPass(cmd);
               },
               true});
}

} // namespace weft::demo
