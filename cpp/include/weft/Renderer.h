#pragma once
// The Vulkan renderer: draws a Scene from a Camera offscreen (read back to memory) or into a
// Window. Every Renderer in a process shares one Vulkan device. Different Renderers may be used
// from different threads at the same time; one Renderer is used by one thread at a time.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>
#include <weft/Error.h>

#include <glm/glm.hpp>

#include <weft/Camera.h>
#include <weft/FrameStats.h>
#include <weft/Image.h>
#include <weft/Scene.h>

namespace weft {

class Window;
namespace debug {
struct RendererAccess;
}
class Renderer;
namespace render { // an internal hook: a pass drawn over present()'s output (render/FrameOverlay.h)
class FrameOverlay;
void setFrameOverlay(Renderer& renderer, FrameOverlay* overlay);
} // namespace render

/// How strands are drawn: 1-pixel lines or camera-facing ribbons (width = hairWidth * thickness).
enum class HairPrimitive { Lines = 0, Ribbons = 1 };
/// Weighted blended OIT weight w(z, alpha) (McGuire & Bavoil 2013, eq. 7-10; the value is the
/// equation's number), z the view-space depth:
enum class OitWeight {
    NearQuadratic = 7, // alpha * clamp(10 / (1e-5 + (|z|/5)^2 + (|z|/200)^6), 1e-2, 3e3)
    NearCubic = 8,     // alpha * clamp(10 / (1e-5 + (|z|/10)^3 + (|z|/200)^6), 1e-2, 3e3)
    FarQuartic = 9,    // alpha * clamp(0.03 / (1e-5 + (|z|/200)^4), 1e-2, 3e3)
    NdcCubic = 10,     // alpha * max(1e-2, 3e3 * (1 - z_ndc)^3)
};
/// How the output pass maps exposed linear radiance to [0, 1] before sRGB encoding.
enum class ToneMap {
    Clamp = 0,   // the seed's look: values above 1 clip
    Aces = 1,    // Narkowicz's fit of the ACES filmic curve (2015)
    AgX = 2,     // Sobotka's AgX base look, sigmoid fit (Blender 4)
    Neutral = 3, // Khronos PBR Neutral (2024): colours below ~0.8 kept as they are
};

struct RenderSettings {
    uint32_t shadowMapSize = 2048; // texels per side of each shadow map
    int pcfRadius = 1;             // PCF kernel (2r+1)^2 taps, r in [0, 7]
    float biasConstant = 0.0005f;  // shadow depth bias in light NDC depth units ...
    float biasSlope = 0.0015f;     // ... plus this times tan(angle between n and l) ...
    float biasMax = 0.01f;         // ... clamped to this
    float normalOffset = 1.5f;     // receiver offset along n, in shadow-map texels
    /// Keep the shadow maps of the last frame when no shadow view and no shadow caster changed
    /// (and the hair's deep opacity maps when no map's view and no strand drawn into it did);
    /// when only some casters moved, keep the others' depth and draw only the moving ones.
    bool reuseShadowMaps = true;
    uint32_t probeSize = 64; // texels per face of the dynamic reflection capture
    /// One bounce of diffuse light from the receivers (instances that cast no shadow: grounds,
    /// walls) onto the shadow casters, and the sky and ambient they hide from them (per-caster
    /// SH9 captures, render/BounceProbes.h).
    bool bounce = true;
    /// Ambient occlusion of a scene without an environment: its constant ambient I_A is read as
    /// a uniform sky and occluded by the shadow casters through a dome of this many soft shadow
    /// lights (0: off; else a multiple of 8 up to 64), like an environment's dome (SPEC §4.5),
    /// with the visibility blurred over `ambientOcclusionBlur` pixels (0: per pixel). The
    /// default, 8, is the best error per millisecond measured on lavapipe: under a sphere the
    /// visibility is within 0.054 of the analytic view factor (16: 0.033 at 1.4x the cost of
    /// 8, 64: 0.01); the forward pass pays for every light.
    uint32_t ambientOcclusion = 8;
    float ambientOcclusionBlur = 4.0f;
    /// Where a dome's shadows are blurred (an environment's dome_blur, or ambientOcclusionBlur),
    /// each pixel of a 2 x 2 block evaluates every fourth dome light, weighted 4, and a gather
    /// pass averages the block's quarters before the blur (interleaved sampling): a quarter of
    /// the dome's cost in the forward pass. Off: every pixel evaluates every light.
    bool domeInterleave = true;
    /// Multisample anti-aliasing of the forward pass: 1, 2, 4 or 8 samples per pixel, lowered
    /// to what the device supports (debug frames are never multisampled).
    uint32_t msaa = 4;
    /// Output: linear radiance times 2^exposure (photographic stops), tone mapped, sRGB
    /// encoded. The linear output (OutputLinear) is neither exposed nor tone mapped.
    float exposure = 0.0f;
    ToneMap toneMap = ToneMap::Clamp;

    // Hair (SPEC §5): drawing, deep opacity maps (self-shadowing from directional lights) and
    // weighted blended order-independent transparency.
    HairPrimitive hairPrimitive = HairPrimitive::Lines;
    float hairWidth = 0.001f;       // ribbon width per unit of strand thickness (world units)
    bool hairDeepOpacity = true;    // DOM for shadow-casting directional lights
    bool hairDomLogSpacing = false; // layer k twice as thick as layer k-1 (else equal layers)
    float hairDomLayerSize = 0.0f;  // d in world units; 0: the hair's depth extent / 3 (or / 7)
    uint32_t hairDomSize = 512;     // texels per side of each deep opacity map
    bool hairTransparency = true;   // WBOIT for hair with transparency > 0 (else opaque lines)
    OitWeight hairOitWeight = OitWeight::NearQuadratic;
    /// Throws InvalidArgument for out-of-range values.
    void validate() const;
};

/// Which images a frame returns besides the 8-bit sRGB colour.
enum FrameOutput : uint32_t {
    OutputColor = 1u << 0,  // RGBA8 sRGB
    OutputLinear = 1u << 1, // linear radiance before encoding (rendered as RGBA16F)
    OutputDebug = 1u << 2,  // position, normal, uv, light depth, shadow visibility, albedo
};

/// Images of one frame, rows top to bottom. Float images are interleaved RGBA floats (linear
/// radiance with the half-float precision it was rendered in, the debug images exact).
struct Frame {
    int width = 0;
    int height = 0;
    ImageU8 color;               // OutputColor
    std::vector<float> linear;   // OutputLinear: r, g, b, a
    std::vector<float> position; // OutputDebug: world x, y, z, coverage (1 drawn / 0 background)
    std::vector<float> normal;   // OutputDebug: shading normal x, y, z (unit), shadow visibility
    std::vector<float> surface;  // OutputDebug: u, v, light-space depth, instance id + 1 (0: none)
    std::vector<float> albedo;   // OutputDebug: T = base colour * texture sample, 1
};

class Renderer {
public:
    Renderer(uint32_t width, uint32_t height, const RenderSettings& settings = {});
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    uint32_t width() const;
    uint32_t height() const;
    void resize(uint32_t width, uint32_t height);
    const RenderSettings& settings() const;
    void setSettings(const RenderSettings& settings);
    /// The MSAA samples per pixel colour frames get on this device for settings().msaa.
    uint32_t msaaSamples() const;

    /// Renders offscreen and returns the outputs asked for (a bitwise OR of FrameOutput).
    Frame render(const Scene& scene, const Camera& camera, uint32_t outputs = OutputColor);

    /// Renders into the window's swapchain and presents. With `capture`, the presented image is
    /// also returned (RGBA8, sRGB) - a screenshot of exactly what the window shows.
    ImageU8 present(Window& window, const Scene& scene, const Camera& camera, bool capture = false);

    /// Statistics of the last frame.
    const FrameStats& stats() const;
    // The last frame's shadow maps, reflection probe and deep opacity maps: weft/Debug.h.
    std::string deviceName() const;

private:
    friend void render::setFrameOverlay(Renderer&, render::FrameOverlay*);
    friend struct debug::RendererAccess; // weft/Debug.h
    struct Impl;
    std::unique_ptr<Impl> mImpl;
};

} // namespace weft
