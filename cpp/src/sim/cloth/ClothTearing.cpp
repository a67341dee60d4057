// Tearing at the level of the rendered surface (issue 17): the grid's triangles tear, and a
// constraint lives while the faces it runs through are there. A stretch or diagonal edge is
// held by either face beside it, a constraint crossing a quad's other diagonal (shear (1,-1),
// bend (k,-k)) needs both faces of every quad it crosses, a bend (k,k) one face of each quad
// along its diagonal. So a torn face removes nothing by itself; the particles part where a
// line of faces tore, and every face still attached keeps all three edges (and is drawn).
// Tethers follow: a region cut off from every anchor loses them, the rest are re-anchored at
// their distance along the cloth.
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <queue>

#include "sim/cloth/ClothImpl.h"

namespace weft {

namespace {
// Face f = 2 * (j * (nx - 1) + i) + t of quad (i, j): t = 0 is (p00, p11, p10), t = 1 is
// (p00, p01, p11); both share the diagonal p00-p11 (the shear constraint (1, 1)).
inline int face(int nx, int i, int j, int t) { return 2 * (j * (nx - 1) + i) + t; }
} // namespace

bool Cloth::Impl::faceOpen(int f) const {
    if (!faceAlive[size_t(f)]) return false;
    if (!anyHole) return true;
    // a face with a hole corner is gone too: nothing may span the hole through it
    const int nx = params.nx, q = f / 2, i = q % (nx - 1), j = q / (nx - 1);
    const int p00 = j * nx + i, p11 = p00 + nx + 1, other = (f % 2) == 0 ? p00 + 1 : p00 + nx;
    return !hole[size_t(p00)] && !hole[size_t(p11)] && !hole[size_t(other)];
}

bool Cloth::Impl::quadAny(int i, int j) const {
    const int nx = params.nx;
    if (i < 0 || j < 0 || i >= nx - 1 || j >= params.ny - 1) return false;
    return faceOpen(face(nx, i, j, 0)) || faceOpen(face(nx, i, j, 1));
}

bool Cloth::Impl::quadBoth(int i, int j) const {
    const int nx = params.nx;
    if (i < 0 || j < 0 || i >= nx - 1 || j >= params.ny - 1) return false;
    return faceOpen(face(nx, i, j, 0)) && faceOpen(face(nx, i, j, 1));
}

bool Cloth::Impl::supported(size_t c) const {
    const int nx = params.nx;
    const int a = constraints[c].a, b = constraints[c].b;
    const int i = a % nx, j = a / nx, dx = b % nx - i, dy = b / nx - j;
    auto alive = [&](int f) { return faceOpen(f); };
    if (dy == 0) { // axial along u: every unit edge has a face above or below
        for (int t = 0; t < dx; ++t) {
            const int x = i + t;
            const bool below = j < params.ny - 1 && alive(face(nx, x, j, 0));
            const bool above = j > 0 && alive(face(nx, x, j - 1, 1));
            if (!below && !above) return false;
        }
        return true;
    }
    if (dx == 0) { // axial along v
        for (int t = 0; t < dy; ++t) {
            const int y = j + t;
            const bool right = i < nx - 1 && alive(face(nx, i, y, 1));
            const bool left = i > 0 && alive(face(nx, i - 1, y, 0));
            if (!right && !left) return false;
        }
        return true;
    }
    if (dx == dy) { // along quad diagonals: a face on either side of each
        for (int t = 0; t < dx; ++t)
            if (!quadAny(i + t, j + t)) return false;
        return true;
    }
    for (int t = 0; t < dx; ++t) // across quads (dy = -dx): through both faces of each
        if (!quadBoth(i + t, j - t - 1)) return false;
    return true;
}

void Cloth::Impl::updateActive() {
    anyHole = std::find(hole.begin(), hole.end(), uint8_t(1)) != hole.end();
    const bool faces = (torn || anyHole) && params.nx > 1 && params.ny > 1;
    for (size_t c = 0; c < constraints.size(); ++c) {
        const bool holeEnd = hole[size_t(constraints[c].a)] || hole[size_t(constraints[c].b)];
        active[c] = !holeEnd && (!faces || supported(c)) ? 1 : 0;
    }
    denseStale = true;
}

bool Cloth::Impl::tearFaces() {
    const int nx = params.nx, ny = params.ny;
    if (nx < 2 || ny < 2) return false;
    const float limit = 1.0f + params.tearStrain;
    const int qx = nx - 1, qy = ny - 1;
    auto x = [&](int i, int j) { return particles[size_t(j * nx + i)].x; };
    auto r = [&](int i, int j) { return rest[size_t(j * nx + i)]; };
    // stretch ratio len / rest (tension tears; compression folds cloth, it does not tear it)
    auto ratio = [&](int i0, int j0, int i1, int j1) {
        return glm::length(x(i1, j1) - x(i0, j0)) / glm::length(r(i1, j1) - r(i0, j0));
    };
    // Each live face's largest stretch over its edges and its quad's other diagonal.
    faceStretch.assign(faceAlive.size(), 0.0f);
    bool any = false;
    for (int j = 0; j < qy; ++j)
        for (int i = 0; i < qx; ++i) {
            const int f0 = face(nx, i, j, 0), f1 = f0 + 1;
            if (!faceAlive[size_t(f0)] && !faceAlive[size_t(f1)]) continue;
            const float shared = std::max(ratio(i, j, i + 1, j + 1), ratio(i, j + 1, i + 1, j));
            if (faceAlive[size_t(f0)])
                faceStretch[size_t(f0)] =
                    std::max({shared, ratio(i, j, i + 1, j), ratio(i + 1, j, i + 1, j + 1)});
            if (faceAlive[size_t(f1)])
                faceStretch[size_t(f1)] =
                    std::max({shared, ratio(i, j, i, j + 1), ratio(i, j + 1, i + 1, j + 1)});
            any |= faceStretch[size_t(f0)] > limit || faceStretch[size_t(f1)] > limit;
        }
    if (!any) return false;
    // Cracks run, they do not start everywhere: a stretched face next to a torn one (a crack
    // tip) tears first, one per tip neighbourhood (the most stretched); only when no tip is
    // over the limit does a new crack start, at the most stretched face of the cloth. So a
    // pulled cloth parts along a few lines of faces instead of shredding where it is
    // uniformly stretched.
    auto around = [&](int f, auto&& visit) {
        const int q = f / 2, i = q % qx, j = q / qx;
        for (int dj = -1; dj <= 1; ++dj)
            for (int di = -1; di <= 1; ++di) {
                const int a = i + di, b = j + dj;
                if (a < 0 || b < 0 || a >= qx || b >= qy) continue;
                const int g = face(nx, a, b, 0);
                visit(g);
                visit(g + 1);
            }
    };
    std::vector<int> tips;
    int worst = -1;
    for (int f = 0; f < int(faceAlive.size()); ++f) {
        const float s = faceStretch[size_t(f)];
        if (!(s > limit)) continue;
        if (worst < 0 || s > faceStretch[size_t(worst)]) worst = f;
        // a tip: it shares an edge with a torn face (a crack ends there)
        const int q = f / 2, i = q % qx, j = q / qx;
        auto dead = [&](int a, int b, int t) {
            return a >= 0 && b >= 0 && a < qx && b < qy && !faceAlive[size_t(face(nx, a, b, t))];
        };
        const bool tip = (f % 2 == 0) ? dead(i, j, 1) || dead(i, j - 1, 1) || dead(i + 1, j, 1)
                                      : dead(i, j, 0) || dead(i - 1, j, 0) || dead(i, j + 1, 0);
        if (tip) tips.push_back(f);
    }
    std::vector<int> doomed;
    for (int f : tips) {
        bool peak = true; // ties go to the lower index, so equal neighbours do not both wait
        around(f, [&](int g) {
            const float sg = faceStretch[size_t(g)];
            if (g != f && std::binary_search(tips.begin(), tips.end(), g) &&
                (sg > faceStretch[size_t(f)] || (sg == faceStretch[size_t(f)] && g < f)))
                peak = false;
        });
        if (peak) doomed.push_back(f);
    }
    if (doomed.empty() && worst >= 0) doomed.push_back(worst);
    if (doomed.empty()) return false;
    for (int f : doomed) faceAlive[size_t(f)] = 0;
    torn = true;
    updateActive();
    if (params.tethers) rebuildTethers();
    return true;
}

void Cloth::Impl::tethersAlongCloth(const std::vector<int>& anchors) {
    // Dijkstra from all anchors at once over the active constraints (rest lengths): each
    // particle gets its nearest anchor along the cloth and that distance, which no
    // inextensible cloth can exceed; particles no anchor reaches get no tether.
    std::vector<std::vector<std::pair<int, float>>> adj(static_cast<size_t>(n));
    for (size_t c = 0; c < constraints.size(); ++c) {
        if (!active[c]) continue;
        adj[size_t(constraints[c].a)].push_back({constraints[c].b, constraints[c].rest});
        adj[size_t(constraints[c].b)].push_back({constraints[c].a, constraints[c].rest});
    }
    std::vector<double> dist(static_cast<size_t>(n), std::numeric_limits<double>::infinity());
    std::vector<int> from(static_cast<size_t>(n), -1);
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
    for (int a : anchors) {
        dist[size_t(a)] = 0.0;
        from[size_t(a)] = a;
        queue.push({0.0, a});
    }
    while (!queue.empty()) {
        const auto [d, k] = queue.top();
        queue.pop();
        if (d > dist[size_t(k)]) continue;
        for (const auto& [q, len] : adj[size_t(k)]) {
            const double nd = d + double(len);
            if (nd < dist[size_t(q)]) {
                dist[size_t(q)] = nd;
                from[size_t(q)] = from[size_t(k)];
                queue.push({nd, q});
            }
        }
    }
    tetherSlots = 1;
    tetherAnchor.assign(size_t(n), 0);
    tetherLength.assign(size_t(n), std::numeric_limits<float>::infinity());
    for (int k = 0; k < n; ++k) {
        tetherAnchor[size_t(k)] = k;
        if (particles[size_t(k)].w == 0.0f || from[size_t(k)] < 0) continue;
        tetherAnchor[size_t(k)] = from[size_t(k)];
        // Never shorter than the path (rounded up), nor than the particle's distance now: a
        // re-anchored tether must not yank a stretched region (a hard projection that moves
        // a particle far in one substep gives it that much velocity).
        const float now =
            glm::length(particles[size_t(k)].x - particles[size_t(from[size_t(k)])].x);
        tetherLength[size_t(k)] = std::max(
            std::nextafter(float(dist[size_t(k)]), std::numeric_limits<float>::infinity()), now);
    }
}

} // namespace weft
