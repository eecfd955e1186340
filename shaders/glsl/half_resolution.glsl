// Half-resolution samples brought to full resolution (thesis ch. 4): a half-resolution sample is
// computed at the top-left pixel of its 2x2 block (full-resolution pixel 2h), and a pixel
// interpolates bilinearly among the four samples around it that lie on its surface (close to its
// position, on its plane, facing its way). Shared by upsample (indirect_method 0) and
// world.upsample (indirect_method 3, world_half_res).
// Needs: frame, gbufferViewDepth, gbufferNormal; gbuffer_position.glsl, screen_space.glsl.
#ifndef SSGI_HALF_RESOLUTION_GLSL
#define SSGI_HALF_RESOLUTION_GLSL

// The compatible samples of halfImage around full-resolution pixel `pixel` (at p, normal n),
// weighted bilinearly (rgb: the weighted sum, a: the sum of the weights; 0 where none is). A
// sample is compatible on p's plane (within 1.5 pixels' world footprint of it), with a normal
// whose cosine to n is at least `facing`, and within 6 footprints times `stretch` of p; one
// whose alpha is below 0.5 (not computed this frame) is left out; halfSize bounds the samples
// read.
vec4 compatibleHalfSamples(sampler2D halfImage, ivec2 halfSize, ivec2 pixel, vec3 p, vec3 n,
                           float stretch, float facing) {
    float footprint = 1.0 / pixelsPerUnit(viewDepth(p));
    float reach = 6.0 * footprint * stretch;
    ivec2 base = (pixel - 1) / 2;
    vec2 f = (vec2(pixel) - vec2(base * 2)) * 0.5;
    vec3 sum = vec3(0.0);
    float weightSum = 0.0;
    for (int j = 0; j < 4; ++j) {
        ivec2 offset = ivec2(j & 1, j >> 1);
        ivec2 h = clamp(base + offset, ivec2(0), halfSize - 1);
        vec4 q = gbufferPosition(h * 2);
        if (q.w == 0.0) continue;
        vec3 nq = texelFetch(gbufferNormal, h * 2, 0).xyz;
        vec3 delta = q.xyz - p;
        if (dot(n, nq) < facing || length(delta) > reach ||
            abs(dot(n, delta)) > 1.5 * footprint)
            continue;
        vec4 halfSample = texelFetch(halfImage, h, 0);
        if (halfSample.a < 0.5) continue;
        float w = (offset.x == 1 ? f.x : 1.0 - f.x) * (offset.y == 1 ? f.y : 1.0 - f.y) + 1e-4;
        sum += w * halfSample.rgb;
        weightSum += w;
    }
    return vec4(sum, weightSum);
}

#endif
