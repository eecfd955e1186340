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

#endif
