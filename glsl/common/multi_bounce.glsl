// The visibility of a sky after the light its occluders reflect: Jimenez et al. 2016
// ("Practical real-time strategies for accurate indirect occlusion", eq. 10) fit it as a cubic in
// the visibility v whose coefficients depend on the albedo rho around the point. Shared by the
// forward pass (shading.glsl) and the dome's gather pass (dome_gather.frag).
float multiBounceVisibility(float v, float rho) {
    float a = 2.0404 * rho - 0.3324, b = -4.7951 * rho + 0.6417, c = 2.7552 * rho + 0.6903;
    return clamp(max(v, ((a * v + b) * v + c) * v), 0.0, 1.0);
}
