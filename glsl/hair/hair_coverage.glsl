// The fraction of a pixel an anti-aliased strand strip covers (hair_vertex.glsl, HAIR_AA): the
// area of the unit pixel square inside a straight strip of width w (pixels) whose centre line
// passes at signed distance x from the pixel's centre, across direction n. A point of the square
// at offset o is inside when |x + o.n| <= w/2, and o.n is the sum of two independent uniforms of
// widths a = |n.x| and b = |n.y| (a trapezoidal density), so the area is F(x + w/2) - F(x - w/2)
// with F that sum's distribution function. Exact for straight strips; a strand narrower than a
// pixel covers w per pixel of its length, as in a supersampled frame.

// P(X + Y <= u), X and Y uniform on [-a/2, a/2] and [-b/2, b/2], a >= b >= 0, a + b >= 1.
float hairTrapezoidCdf(float u, float a, float b) {
    float lo = 0.5 * (a - b), hi = 0.5 * (a + b);
    if (u <= -hi) return 0.0;
    if (u >= hi) return 1.0;
    if (b < 1e-4) return u / a + 0.5;
    if (u < -lo) return (u + hi) * (u + hi) / (2.0 * a * b);
    if (u <= lo) return 0.5 + u / a;
    return 1.0 - (hi - u) * (hi - u) / (2.0 * a * b);
}

// strip: (x, w) as above; ends: the distances from the pixel's centre to the strand's root and
// tip along it (pixels, > 0 inside); across: unit direction across the strand (screen pixels).
// Along the strand the pixel square projects onto the same trapezoid, and an end cuts the
// coverage by the share of it on the strand's side (a product: exact for strands along the
// pixel grid).
float hairCoverage(vec2 strip, vec2 ends, vec2 across) {
    float a = max(abs(across.x), abs(across.y)), b = min(abs(across.x), abs(across.y));
    float h = 0.5 * strip.y;
    float inside = hairTrapezoidCdf(strip.x + h, a, b) - hairTrapezoidCdf(strip.x - h, a, b);
    return clamp(inside * hairTrapezoidCdf(ends.x, a, b) * hairTrapezoidCdf(ends.y, a, b), 0.0,
                 1.0);
}
