// Environment: cached filtering keyed by content version.
#include <weft/Environment.h>

#include "IblValidate.h"

namespace weft {

Environment::Environment(CubeMap radiance) : mRadiance(std::move(radiance)) {
    requireCube(mRadiance, "environment radiance");
    mStats.version = mVersion;
}

void Environment::setRadiance(CubeMap radiance) {
    requireCube(radiance, "environment radiance");
    std::lock_guard<std::mutex> lock(mMutex);
    mRadiance = std::move(radiance);
    ++mVersion;
    invalidate();
}

void Environment::invalidate() {
    mHaveSh = false;
    mIrradiance.clear();
    mSpecular.clear();
    mDomes.clear();
    mStats.version = mVersion;
}

uint64_t Environment::version() const {
    std::lock_guard<std::mutex> lock(mMutex);
    return mVersion;
}

Sh9 Environment::irradianceSh() {
    std::lock_guard<std::mutex> lock(mMutex);
    return shLocked();
}

Sh9 Environment::shLocked() {
    mStats.lastRefiltered = !mHaveSh;
    if (mHaveSh) {
        ++mStats.cacheHits;
        return mSh;
    }
    mSh = projectSh9(mRadiance);
    mHaveSh = true;
    ++mStats.filterRuns;
    return mSh;
}

CubeMap Environment::irradianceMap(int size) {
    std::lock_guard<std::mutex> lock(mMutex);
    auto it = mIrradiance.find(size);
    if (it != mIrradiance.end()) {
        ++mStats.cacheHits;
        mStats.lastRefiltered = false;
        return it->second;
    }
    CubeMap map = irradianceFromSh(shLocked(), size);
    ++mStats.filterRuns;
    mStats.lastRefiltered = true;
    return mIrradiance.emplace(size, std::move(map)).first->second;
}

CubeMap Environment::specularChain(int size, int levels, int samples) {
    std::lock_guard<std::mutex> lock(mMutex);
    const auto key = std::make_tuple(size, levels, samples);
    auto it = mSpecular.find(key);
    if (it != mSpecular.end()) {
        ++mStats.cacheHits;
        mStats.lastRefiltered = false;
        return it->second;
    }
    CubeMap chain = prefilterGgx(mRadiance, size, levels, samples);
    ++mStats.filterRuns;
    mStats.lastRefiltered = true;
    return mSpecular.emplace(key, std::move(chain)).first->second;
}

ShadowDome Environment::shadowDome(int count, DomeLayout layout) {
    std::lock_guard<std::mutex> lock(mMutex);
    const auto key = std::make_pair(count, int(layout));
    auto it = mDomes.find(key);
    if (it != mDomes.end()) {
        ++mStats.cacheHits;
        mStats.lastRefiltered = false;
        return it->second;
    }
    ShadowDome dome(mRadiance, count, layout);
    ++mStats.filterRuns;
    mStats.lastRefiltered = true;
    return mDomes.emplace(key, std::move(dome)).first->second;
}

EnvironmentStats Environment::stats() const {
    std::lock_guard<std::mutex> lock(mMutex);
    return mStats;
}

} // namespace weft
