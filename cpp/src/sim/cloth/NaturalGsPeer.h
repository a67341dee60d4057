#pragma once
// A benchmark peer of the cloth solver (issue 17 item 8): position-based dynamics with plain
// Gauss-Seidel in natural order, what a straightforward serial implementation does. Scalar
// float32, one thread, written apart from weft's solver (no batches, no SIMD, no SoA) so that
// it measures the accuracy one sweep in natural order reaches and the speed such a loop runs
// at. Bound to Python as weft._core._NaturalGsPeer for `python -m weft.bench cloth`; not
// part of the public API.
#include <vector>

#include <glm/glm.hpp>

namespace weft::cloth {

struct NaturalGsPeerSetup {
    std::vector<glm::vec3> positions;
    std::vector<float> inverseMass; // 0 = pinned
    std::vector<int> a, b;          // constraints, projected in this order
    std::vector<float> rest, compliance;
    std::vector<int> tetherParticle, tetherAnchor; // one-sided |x_p - x_anchor| <= length
    std::vector<float> tetherLength;
    glm::vec3 gravity{0.0f, -9.81f, 0.0f};
    float damping = 0.99f; // velocity factor per 1/60 s
    int iterations = 1, substeps = 1;
};

class NaturalGsPeer {
public:
    explicit NaturalGsPeer(NaturalGsPeerSetup setup); // throws InvalidArgument on bad indices
    void step(float dt);
    const std::vector<glm::vec3>& positions() const { return mX; }
    double kineticEnergy(double particleMass) const;

private:
    NaturalGsPeerSetup mS;
    std::vector<glm::vec3> mX, mPrev;
    std::vector<float> mLambda;
    float mLastH = 1.0f / 60.0f;
};

} // namespace weft::cloth
