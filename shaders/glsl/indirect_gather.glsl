// One-bounce indirect light from the reflective shadow map (thesis 3.3; Dachsbacher and
// Stamminger 2005): every RSM texel q is a virtual point light of flux Phi_q, and
// E(p) = sum_q Phi_q max(0, n_p . D) max(0, n_q . -D) / (pi |q - p|^2), D = (q - p)/|q - p|
// (equations 9-10 with the 1/pi of a diffuse emitter). VPLS texels are gathered around p's
// projection in a polar pattern whose density falls as 1/r (shared_vpls.h vplPattern); each is
// weighted by its distance r to undo that density, so the sum estimates the sum over every
// texel the pattern reaches. An optional screen-space visibility test marches from p toward q at
// log-spaced steps (equation 8) and rejects the VPL where a step has just crossed behind a
// surface the G-buffer holds (indirect_visibility.glsl).
// Needs: frame, rsm_vpl.glsl, rsmVpls, gbuffer_position.glsl, gbufferNormal, VPLS, VISIBILITY,
// VISIBILITY_STEPS, screen_space.glsl.

#include "indirect_visibility.glsl"

// Irradiance / pi at p (normal n) from the RSM's VPLs: all VPLS of the pattern (k = 1), or the
// interleaved subset `subset` of k*k (shared_vpls.h vplSubset), weighted so that each subset alone
// estimates the whole pattern's sum and their mean is that sum.
// `directional` receives the same VPLs' light, before p's cosine and visibility, as an L1
// spherical harmonic of its luminance (x = sum of c, yzw = sum of c D, for c the VPL's luminance
// towards p): f(m) = x / 4 + dot(yzw, m) / 2 approximates the irradiance / pi a normal m
// would receive, which lets the interleaved method's filter carry a neighbour's estimate over
// to another normal (indirect_reconstruct.comp).
vec3 gatherIndirect(vec3 p, vec3 n, float rotation, float radiusScale, float radius,
                    float stratum, int subset, int k, out vec4 directional) {
    int subsets = k * k;
    vec4 clip = frame.lightViewProjection * vec4(p, 1.0);
    // The pattern is centred on p's projection (the map's centre when p is behind the light) and
    // clamped into the map. With radius 0 it covers the whole map, so that every VPL can be
    // drawn (a ceiling above a downward spot sees only VPLs far from its projection); a radius
    // > 0 is the RSM paper's r_max, cheaper and biased.
    vec2 center = clip.w > 0.0 ? clip.xy / clip.w * 0.5 + 0.5 : vec2(0.5);
    VplPattern pattern = vplPattern(clamp(center, vec2(0.0), vec2(1.0)), radius * radiusScale);
    float size = frame.lightFrustum.w;
    // Texels per sample: a sample at distance r stands for the map's area 1 / (VPLS density),
    // total r / VPLS (shared_vpls.h vplPattern), of size^2 texels per unit area.
    float weightScale = size * size * pattern.total / float(VPLS) * float(subsets);
    vec3 irradiance = vec3(0.0);
    directional = vec4(0.0);
    for (int j = 0; j < vplSubsetSize(subset, VPLS, k); ++j) {
        int i = vplOfSubset(subset, j, k);
        float r;
        vec2 uv = vplPatternPoint(pattern, i, VPLS, stratum, rotation, r);
        if (any(lessThan(uv, vec2(0.0))) || any(greaterThanEqual(uv, vec2(1.0)))) continue;
        ivec2 texel = ivec2(uv * size);
        uvec4 vpl = texelFetch(rsmVpls, texel, 0); // one read: rsm_vpl.glsl
        if (!rsmTexelDrawn(vpl)) continue;
        vec3 q = rsmTexelPosition(texel, vpl);
        vec3 toVpl = q - p;
        float distance2 = dot(toVpl, toVpl);
        // Clamp the distance to the VPL's own footprint: a sample cannot deliver more than the
        // area it stands for, which removes the 1/d^2 spike of VPLs right next to p. A sample
        // stands for weightScale * r texels (its subset's k^2 and the pattern's density at r:
        // far from the pattern's centre, where samples are sparse, many), and the clamp is the
        // radius of a disk of a quarter of that area, at least k texels. The quarter is measured
        // (docs/effects.md): the whole disk's radius removes every spike but darkens the Cornell
        // boxes' corners; k texels alone let a far sample that lands next to p (a floor VPL at a
        // wall's foot) light one pixel 20-50 times too bright in one frame out of ten.
        float texels = sqrt(max(weightScale * r / (4.0 * PI), float(k * k)));
        float footprint = distance(q, frame.lightPosition.xyz) * 2.0 * frame.lightFrustum.z /
                          size * texels;
        float d2 = max(distance2, footprint * footprint);
        vec3 D = toVpl * inversesqrt(max(distance2, tinyLength2()));
        float cosP = max(dot(n, D), 0.0);
        float cosQ = max(dot(rsmTexelNormal(vpl), -D), 0.0);
        vec3 flux = rsmTexelFlux(vpl);
        directional +=
            dot(flux, vec3(0.2126, 0.7152, 0.0722)) * cosQ / (PI * d2) * r * vec4(1.0, D);
        // A VPL outside the spot's cone reflects nothing: no visibility test for it.
        if (cosP * cosQ <= 0.0 || all(equal(flux, vec3(0.0)))) continue;
        if (VISIBILITY != 0 && !vplVisible(p, q, rsmTexelNormal(vpl))) continue;
        irradiance += flux * (cosP * cosQ / (PI * d2)) * r;
    }
    directional *= weightScale / PI;
    return irradiance * weightScale / PI;
}
