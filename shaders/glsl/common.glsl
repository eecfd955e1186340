// GLSL helpers shared by the passes.
#ifndef SSGI_COMMON_GLSL
#define SSGI_COMMON_GLSL

const float PI = 3.14159265358979;

// glTF KHR_lights_punctual spot attenuation: linear in cos between the cones, squared.
float spotAttenuation(vec3 fromLight, vec3 axis, float cosOuter, float cosInner) {
    float cd = dot(fromLight, axis);
    float t = clamp((cd - cosOuter) / max(cosInner - cosOuter, 1e-4), 0.0, 1.0);
    return t * t;
}

// Linear distance along the view axis from a [0,1] depth of a ZO perspective projection.
float linearDepth(float depth, float znear, float zfar) {
    return znear * zfar / (zfar - depth * (zfar - znear));
}

vec3 skyRadiance(vec3 direction, vec3 zenith, vec3 horizon, vec3 ground) {
    return direction.y >= 0.0 ? mix(horizon, zenith, direction.y) : ground;
}

// Per-pixel rotation of a sampling pattern (interleaved gradient noise, Jimenez 2014): plays
// the role of the thesis's random-vector texture, decorrelating neighbouring pixels.
float pixelRotation(ivec2 pixel) {
    return 2.0 * PI * fract(52.9829189 * fract(0.06711056 * float(pixel.x) +
                                               0.00583715 * float(pixel.y)));
}

// Where in its radial stratum a pattern's sample lies this frame. For a cached effect the
// renderer moves `offset` (the constants' pattern.w) over [0, 1) frame by frame, so that the
// accumulated frames fill the radii between one frame's samples, as the turn fills the angles;
// negative (not cached): the single frame's fixed place, `fixedAt`.
float radialOffset(float offset, float fixedAt) {
    return offset < 0.0 ? fixedAt : offset;
}

// Point i of n on the unit disk, evenly spread (Vogel's golden-angle spiral), turned by
// `rotation`; `offset` places it within its ring (0.5: the middle).
vec2 vogelDisk(int i, int n, float rotation, float offset) {
    float r = sqrt((float(i) + offset) / float(n));
    float theta = float(i) * 2.39996323 + rotation;
    return r * vec2(cos(theta), sin(theta));
}

vec2 vogelDisk(int i, int n, float rotation) {
    return vogelDisk(i, n, rotation, 0.5);
}

// A tangent frame around a unit normal.
mat3 tangentFrame(vec3 n) {
    vec3 helper = abs(n.y) < 0.999 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
    vec3 t = normalize(cross(helper, n));
    return mat3(t, cross(n, t), n);
}

#endif
