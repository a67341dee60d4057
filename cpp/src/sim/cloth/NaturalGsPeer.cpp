// The natural-order Gauss-Seidel peer (see NaturalGsPeer.h): Verlet with damping, then per
// sweep every distance constraint in list order (XPBD when compliant), then the tethers.
#include "sim/cloth/NaturalGsPeer.h"

#include <cmath>
#include <string>

#include <weft/Error.h>

namespace weft::cloth {

NaturalGsPeer::NaturalGsPeer(NaturalGsPeerSetup setup) : mS(std::move(setup)) {
    const size_t n = mS.positions.size();
    const size_t m = mS.a.size();
    if (mS.inverseMass.size() != n || mS.b.size() != m || mS.rest.size() != m ||
        mS.compliance.size() != m || mS.tetherAnchor.size() != mS.tetherParticle.size() ||
        mS.tetherLength.size() != mS.tetherParticle.size())
        throw InvalidArgument("natural GS peer: array lengths differ");
    auto check = [&](const std::vector<int>& v) {
        for (int k : v)
            if (k < 0 || size_t(k) >= n)
                throw InvalidArgument("natural GS peer: particle index out of range");
    };
    check(mS.a), check(mS.b), check(mS.tetherParticle), check(mS.tetherAnchor);
    if (mS.iterations < 1 || mS.substeps < 1)
        throw InvalidArgument("natural GS peer: iterations and substeps >= 1");
    mX = mS.positions;
    mPrev = mX;
    mLambda.assign(m, 0.0f);
}

void NaturalGsPeer::step(float dt) {
    const float h = dt / float(mS.substeps);
    const float d = std::pow(mS.damping, h * 60.0f);
    const glm::vec3 gh2 = mS.gravity * (h * h);
    const std::vector<float>& w = mS.inverseMass;
    for (int s = 0; s < mS.substeps; ++s) {
        for (size_t k = 0; k < mX.size(); ++k) {
            const glm::vec3 x = mX[k];
            if (w[k] > 0.0f) mX[k] = x + d * (x - mPrev[k]) + gh2;
            mPrev[k] = x;
        }
        std::fill(mLambda.begin(), mLambda.end(), 0.0f);
        for (int it = 0; it < mS.iterations; ++it) {
            for (size_t c = 0; c < mS.a.size(); ++c) {
                glm::vec3& xa = mX[size_t(mS.a[c])];
                glm::vec3& xb = mX[size_t(mS.b[c])];
                const float wa = w[size_t(mS.a[c])], wb = w[size_t(mS.b[c])];
                const glm::vec3 e = xb - xa;
                const float len = std::sqrt(glm::dot(e, e));
                if (len < 1e-12f || wa + wb <= 0.0f) continue;
                const float alpha = mS.compliance[c] / (h * h);
                const float dl = (mS.rest[c] - len - alpha * mLambda[c]) / (wa + wb + alpha);
                mLambda[c] += dl;
                const glm::vec3 corr = e * (dl / len);
                xa -= wa * corr;
                xb += wb * corr;
            }
            for (size_t t = 0; t < mS.tetherParticle.size(); ++t) {
                glm::vec3& x = mX[size_t(mS.tetherParticle[t])];
                const glm::vec3 anchor = mX[size_t(mS.tetherAnchor[t])];
                const glm::vec3 e = x - anchor;
                const float len = std::sqrt(glm::dot(e, e));
                if (len > mS.tetherLength[t]) x = anchor + e * (mS.tetherLength[t] / len);
            }
        }
    }
    mLastH = h;
}

double NaturalGsPeer::kineticEnergy(double particleMass) const {
    double e = 0.0;
    for (size_t k = 0; k < mX.size(); ++k) {
        const glm::vec3 v = (mX[k] - mPrev[k]) / mLastH;
        e += 0.5 * particleMass * double(glm::dot(v, v));
    }
    return e;
}

} // namespace weft::cloth
