#pragma once
// One bounce of diffuse light (issue 18): light that the scene's receivers (instances that cast
// no shadow: grounds, walls) reflect onto its shadow casters, and the part of the sky the
// receivers hide from them. Each caster gets a small cube capture of the receivers alone, taken
// from the centre of its bounds and shaded as the frame shades them; bounce_sh.frag projects
// every capture onto SH9 irradiance at BOUNCE_POINTS points of the caster (its centre and 14
// on the ellipsoid its bounds hold: gpu_types.h), three sets per point:
//   0  the receivers' radiance                   -> added as diffuse light (K_D T E / pi),
//   1  the environment's radiance they hide      -> taken from the environment's irradiance,
//   2  the solid angle they cover (radiance 1)   -> the fraction of the ambient I_A kept out.
// Casters do not see each other or themselves here: the dome (and shadow maps) carry their
// occlusion, so nothing is counted twice. The captures' depths place the receivers, so each
// point sees them from where it is: a fragment blends the points around it (bounce.glsl). The
// centre alone saw the ground under a sphere where the sphere's lower side sees the ground
// beside it (the unlit side 17-31% too dark against Mitsuba under a sun). Taken in two rounds: the
// second shows the receivers with the light the casters send them (caster_bounce.glsl, from the
// first round's SH), so the light going back and forth between a caster and the ground beside it is
// counted twice over, not once. Captured again only when what they show may have changed (the same
// key as the reflection capture's).
#include <cstdint>
#include <vector>

#include <weft/Renderer.h>
#include <weft/Scene.h>

#include "render/FrameData.h"
#include "render/GpuTypes.h"
#include "vk/Resources.h"

namespace weft::render {

class BounceProbes {
public:
    static constexpr uint32_t kMaxProbes = gpu::MAX_BOUNCE_CASTERS; // casters beyond get none
    static constexpr uint32_t kFaceSize = 16;               // texels per face: SH9 needs no more
    static constexpr uint32_t kShColumns = 27;              // three sets of nine coefficients
    static constexpr uint32_t kPoints = gpu::BOUNCE_POINTS; // rows per probe in sh()
    static constexpr uint32_t kRadianceColumns = 9; // a caster's radiance, SH9 (see radiance())
    static constexpr uint32_t kRounds = 2;          // captures per probe and face (see above)
    static constexpr VkFormat kShFormat = VK_FORMAT_R32G32B32A32_SFLOAT;

    explicit BounceProbes(vk::Context& ctx) : mCtx(ctx) {}

    /// Picks this frame's probes (settings.bounce, casters with receivers to see), marks their
    /// instances (GpuInstance::flags.y = probe + 1) and the frame (GpuFrame::sky.z = 1), and
    /// returns whether the captures must be taken again.
    bool prepare(const Scene& scene, FrameData& data, const RenderSettings& settings);
    /// The next prepare() captures again (the renderer's settings changed).
    void invalidate() { mKey.clear(); }
    uint32_t count() const { return uint32_t(mPositions.size()); }
    const glm::vec3& position(uint32_t probe) const { return mPositions[probe]; }
    vk::Image& faces() { return mFaces; } // layer 6 probe + face, kHdrFormat
    vk::Image& depth() { return mDepth; } // layer 6 probe + face, like faces()
    const glm::vec3& half(uint32_t probe) const { return mHalves[probe]; } // its bounds' extents
    vk::Image& sh() { return mSh; } // row: probe * kPoints + point, column: 9 set + coefficient
    /// Row: probe * kPoints + point, column: capture texel (face S + v) S + u: the direction
    /// and solid angle the point sees it at (bounce_geometry.frag), for the projection.
    vk::Image& geometry() { return mGeometry; }
    vk::Image& shFirst() { return mShFirst; } // the first round's (what the second one reads)
    /// Row: probe, column: coefficient k of the radiance the caster sends out as the proxy
    /// sphere of caster_bounce.glsl (bounce_radiance.frag, every frame with probes).
    vk::Image& radiance() { return mRadiance; }
    vk::Image& radianceFirst() { return mRadianceFirst; } // from shFirst, for the second round

private:
    vk::Context& mCtx;
    vk::Image mFaces, mDepth, mGeometry, mSh, mShFirst, mRadiance, mRadianceFirst;
    std::vector<glm::vec3> mPositions, mHalves;
    std::vector<uint64_t> mKey;
};

} // namespace weft::render
