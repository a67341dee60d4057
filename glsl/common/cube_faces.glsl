// The faces of weft's cube captures (render/ReflectionProbe.cpp renders them so): face f's
// (major axis, u axis, v axis) are kCubeAxes[3 f .. 3 f + 2]; texel (i, j) of an S x S face
// looks along ma + u su + v sv with u = (i + 1/2) 2 / S - 1, v likewise.
const vec3 kCubeAxes[18] = vec3[18](
    vec3(1, 0, 0), vec3(0, 0, -1), vec3(0, -1, 0), vec3(-1, 0, 0), vec3(0, 0, 1), vec3(0, -1, 0),
    vec3(0, 1, 0), vec3(1, 0, 0), vec3(0, 0, 1), vec3(0, -1, 0), vec3(1, 0, 0), vec3(0, 0, -1),
    vec3(0, 0, 1), vec3(1, 0, 0), vec3(0, -1, 0), vec3(0, 0, -1), vec3(-1, 0, 0), vec3(0, -1, 0));

// The face direction d falls on and its texture coordinates there (0..1).
int cubeFace(vec3 d, out vec2 uv) {
    vec3 a = abs(d);
    int face = a.x >= a.y && a.x >= a.z ? (d.x > 0.0 ? 0 : 1)
             : a.y >= a.z              ? (d.y > 0.0 ? 2 : 3)
                                       : (d.z > 0.0 ? 4 : 5);
    float m = dot(d, kCubeAxes[3 * face]);
    uv = 0.5 * vec2(dot(d, kCubeAxes[3 * face + 1]), dot(d, kCubeAxes[3 * face + 2])) / m + 0.5;
    return face;
}
