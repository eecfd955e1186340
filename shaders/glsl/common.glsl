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

// Irradiance / pi from the whole unoccluded sky on a surface with normal n: (1/pi) times the
// integral of skyRadiance(w) max(n.w, 0) over the sphere, in closed form in c = n.y. The sky is
// ground below the horizon, horizon + (zenith - horizon) w.y above it, so three integrals:
// - the cosine lobe's share above the horizon, (1 + c) / 2, and below it, (1 - c) / 2 (the
//   view factors of the two half-spaces from a tilted plane);
// - (1/pi) * integral of w.y max(n.w, 0) over the upper hemisphere: the integral of two clamped
//   cosines whose axes are g = acos(c) apart, (2/3)((pi - g) cos g + sin g), over pi.
// c = 1 gives horizon/3 + 2 zenith/3; c = -1 gives ground. Evaluating skyRadiance along n instead
// is exact only for a constant sky (and turns a flat-shaded model's n.y = 0 edges into steps).
vec3 skyIrradianceOverPi(vec3 n, vec3 zenith, vec3 horizon, vec3 ground) {
    float c = clamp(n.y, -1.0, 1.0);
    float g = acos(c);
    float gradient = (2.0 / (3.0 * PI)) * ((PI - g) * c + sqrt(max(1.0 - c * c, 0.0)));
    return ground * (0.5 - 0.5 * c) + horizon * (0.5 + 0.5 * c) + (zenith - horizon) * gradient;
}

// A unit vector as two numbers in [-1, 1] and back (the octahedral map).
vec2 octahedralEncode(vec3 v) {
    v /= abs(v.x) + abs(v.y) + abs(v.z);
    vec2 e = v.xy;
    if (v.z < 0.0) e = (1.0 - abs(v.yx)) * vec2(v.x >= 0.0 ? 1.0 : -1.0, v.y >= 0.0 ? 1.0 : -1.0);
    return e;
}
vec3 octahedralDecode(vec2 e) {
    vec3 v = vec3(e, 1.0 - abs(e.x) - abs(e.y));
    float t = max(-v.z, 0.0);
    v.xy -= t * vec2(v.x >= 0.0 ? 1.0 : -1.0, v.y >= 0.0 ? 1.0 : -1.0);
    return normalize(v);
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
