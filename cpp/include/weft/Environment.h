#pragma once
// A captured environment that filters only when it changes: irradiance SH9, irradiance maps, GGX
// chains and shadow-light domes are cached against a content version that setRadiance() bumps
// (SPEC §6: static environment -> no re-filtering). Thread-safe.
#include <cstdint>
#include <map>
#include <mutex>
#include <tuple>

#include <weft/CubeMap.h>
#include <weft/IblFilter.h>
#include <weft/ShadowDome.h>

namespace weft {

struct EnvironmentStats {
    uint64_t version = 0;        ///< content version (1 after construction, +1 per setRadiance)
    int filterRuns = 0;          ///< computations done (SH projections, maps, chains)
    int cacheHits = 0;           ///< requests answered from the cache
    bool lastRefiltered = false; ///< whether the latest request computed anything
};

class Environment {
public:
    explicit Environment(CubeMap radiance);

    /// Replaces the radiance and invalidates every cached result.
    void setRadiance(CubeMap radiance);
    const CubeMap& radiance() const { return mRadiance; }
    uint64_t version() const;

    Sh9 irradianceSh();
    /// Irradiance cube map of `size` evaluated from SH9.
    CubeMap irradianceMap(int size);
    /// GGX prefiltered chain (see prefilterGgx).
    CubeMap specularChain(int size, int levels, int samples);
    /// Dome of `count` shadow lights with intensities from this environment (see ShadowDome).
    ShadowDome shadowDome(int count, DomeLayout layout = DomeLayout::Fibonacci);
    EnvironmentStats stats() const;

private:
    void invalidate();
    Sh9 shLocked();

    mutable std::mutex mMutex;
    CubeMap mRadiance;
    uint64_t mVersion = 1;
    bool mHaveSh = false;
    Sh9 mSh;
    std::map<int, CubeMap> mIrradiance;
    std::map<std::tuple<int, int, int>, CubeMap> mSpecular;
    std::map<std::pair<int, int>, ShadowDome> mDomes;
    EnvironmentStats mStats;
};

} // namespace weft
