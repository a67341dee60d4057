// The points of a caster at which its bounce capture is projected (gpu_types.h BOUNCE_POINTS,
// bounce_sh.frag), as directions from its centre scaled by its bounds' half extents: 0 the
// centre, 1-6 the faces' centres (+x, -x, +y, -y, +z, -z), 7-14 the corners (7 + (x > 0) +
// 2 (y > 0) + 4 (z > 0)), all on the ellipsoid the bounds hold.
vec3 bouncePointDirection(int point) {
    if (point == 0) return vec3(0.0);
    if (point <= 6) {
        int axis = (point - 1) / 2;
        vec3 d = vec3(0.0);
        d[axis] = (point - 1) % 2 == 0 ? 1.0 : -1.0;
        return d;
    }
    int b = point - 7;
    return vec3((b & 1) != 0 ? 1.0 : -1.0, (b & 2) != 0 ? 1.0 : -1.0, (b & 4) != 0 ? 1.0 : -1.0) *
           0.57735027;
}

// The points around direction a (not zero) and their weights: a's cube face is cut into four
// triangles (its centre and two corners each), and a is interpolated within its triangle, so
// the weights run on continuously over the faces' edges.
void bouncePointsAround(vec3 a, out ivec3 points, out vec3 weights) {
    vec3 m = abs(a);
    int axis = m.x >= m.y && m.x >= m.z ? 0 : m.y >= m.z ? 1 : 2;
    int ua = axis == 0 ? 1 : 0, va = axis == 2 ? 1 : 2;
    float s = a[axis] > 0.0 ? 1.0 : -1.0;
    float u = a[ua] / m[axis], v = a[va] / m[axis];
    // the triangle towards the edge at the larger of |u|, |v|; t runs along that edge
    bool alongV = abs(u) >= abs(v);
    float big = alongV ? u : v, small = alongV ? v : u;
    float e = max(abs(big), 1e-6);
    float t = clamp(0.5 * (small / e + 1.0), 0.0, 1.0);
    vec3 c0 = vec3(0.0), c1 = vec3(0.0);
    c0[axis] = c1[axis] = s;
    c0[alongV ? ua : va] = c1[alongV ? ua : va] = big >= 0.0 ? 1.0 : -1.0;
    c0[alongV ? va : ua] = -1.0;
    c1[alongV ? va : ua] = 1.0;
    points = ivec3(1 + 2 * axis + (s > 0.0 ? 0 : 1),
                   7 + int(c0.x > 0.0) + 2 * int(c0.y > 0.0) + 4 * int(c0.z > 0.0),
                   7 + int(c1.x > 0.0) + 2 * int(c1.y > 0.0) + 4 * int(c1.z > 0.0));
    weights = vec3(1.0 - abs(big), abs(big) * (1.0 - t), abs(big) * t);
}
