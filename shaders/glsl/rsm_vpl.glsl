// The reflective shadow map's texels, each a virtual point light (Dachsbacher and Stamminger
// 2005). The RSM keeps one RGBA32UI texel a VPL, everything a gather reads of it in one fetch of
// 16 bytes: the gathers read the map at scattered places, where each read of a separate image
// costs lavapipe a cache miss (the interleaved gather on the bunny at 256x256, uncached and
// without its visibility test: 52 ms with depth, normal and flux in three images, 15 ms with the
// depth's read alone).
//   x  the surface's albedo: the square root of each channel in 10 bits (dark albedos keep their
//      precision)
//   y  the share of the light's intensity the texel sends on (float bits): the spot's falloff
//      times the texel's solid angle. The flux is albedo x light colour x share, so the share is
//      a pure number, the same for a scene in any unit and far from 16-bit floats' limits
//   z  the normal, turned to face the light, octahedral in two 16-bit snorms
//   w  the distance along the light's axis (float bits), 0 where nothing was drawn; the VPL's
//      position is the ray through the texel's centre taken to it (pixel_to_world.glsl)
// The shadow pass reads the RSM's depth target instead, as a shadow map.
// Needs: frame, common.glsl; for rsmTexelPosition, loadPixelToWorld() called in main().
#ifndef SSGI_RSM_VPL_GLSL
#define SSGI_RSM_VPL_GLSL

#include "pixel_to_world.glsl"

// The texel rsm.frag writes.
uvec4 packRsmTexel(vec3 albedo, float share, vec3 normal, float axisDepth) {
    uvec3 a = uvec3(round(sqrt(clamp(albedo, 0.0, 1.0)) * 1023.0));
    return uvec4(a.r | (a.g << 10) | (a.b << 20), floatBitsToUint(share),
                 packSnorm2x16(octahedralEncode(normal)), floatBitsToUint(axisDepth));
}

bool rsmTexelDrawn(uvec4 t) {
    return t.w != 0u;
}
vec3 rsmTexelFlux(uvec4 t) {
    vec3 root = vec3(uvec3(t.x, t.x >> 10, t.x >> 20) & 1023u) / 1023.0;
    return root * root * frame.lightColor.rgb * uintBitsToFloat(t.y);
}
vec3 rsmTexelNormal(uvec4 t) {
    return octahedralDecode(unpackSnorm2x16(t.z));
}
vec3 rsmTexelPosition(ivec2 texel, uvec4 t) {
    return worldAt(rsmToWorld, texel, uintBitsToFloat(t.w));
}

#endif
