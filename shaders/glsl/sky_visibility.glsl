// The sky's visibility beyond the screen at one surface point: how much of the sky's light
// reaches it past the occluders screen-space AO cannot see (roofs, arcades, anything off
// screen), from the sky visibility maps (sky_maps.glsl) and the scene's floors and walls, which
// are tested exactly (SkyTriangles, shared.h). Per map direction w_k, the point is looked up in
// that map and its ray toward w_k tested against those triangles; an occluder counts only beyond
// `aoReach` (the AO radius: nearer ones are the AO's, so none is counted twice). The result is a
// ratio per colour channel,
//   sum_k L(w_k) V_k max(n.w_k, 0) / sum_k L(w_k) max(n.w_k, 0),
// the fraction of the unoccluded sky's irradiance that arrives: 1 where nothing far blocks the
// sky. sky_visibility.comp computes it at every pixel, world_sky_visibility.comp at the world
// cache's cells.
// Needs: frame, common.glsl, sky_maps.glsl, the sampler skyMaps (the depth atlas) and the
// uniform block `exact` (SkyTriangles).
#ifndef SSGI_SKY_VISIBILITY_GLSL
#define SSGI_SKY_VISIBILITY_GLSL

// Whether the ray from p toward w meets one of the exact triangles farther than `reach`
// (Moller and Trumbore 1997).
bool blockedExactly(vec3 p, vec3 w, float reach) {
    for (int i = 0; i < exact.count.x; ++i) {
        vec3 a = exact.corners[3 * i].xyz;
        vec3 e1 = exact.corners[3 * i + 1].xyz - a, e2 = exact.corners[3 * i + 2].xyz - a;
        vec3 side = cross(w, e2);
        float det = dot(e1, side);
        if (abs(det) < 1e-20) continue; // the ray runs along the triangle's plane
        vec3 fromA = p - a;
        float u = dot(fromA, side) / det;
        if (u < 0.0 || u > 1.0) continue;
        vec3 up = cross(fromA, e1);
        float v = dot(w, up) / det;
        if (v < 0.0 || u + v > 1.0) continue;
        if (dot(e2, up) / det > reach) return true;
    }
    return false;
}

// The visibility at surface point `position` with unit normal n, an occluder counting beyond
// `aoReach`, the point first moved `normalOffset` off the surface along its normal so that it
// does not shadow itself within a texel of the maps.
vec3 skyVisibilityAt(vec3 position, vec3 n, SkyMapView maps, float aoReach, float normalOffset) {
    float diameter = 2.0 * maps.sphere.w;
    vec3 p = position + n * normalOffset;
    vec3 open = vec3(0.0), arriving = vec3(0.0);
    for (int k = 0; k < maps.tile.y; ++k) {
        vec3 w = skyMapDirection(k, maps.tile.y);
        float cosine = dot(n, w);
        if (cosine <= 0.0) continue;
        vec3 weight = skyRadiance(w, frame.skyZenith.rgb, frame.skyHorizon.rgb,
                                  frame.skyGround.rgb) * cosine;
        vec3 q = skyMapProject(p, w, maps.sphere);
        // Outside the map's square the ray toward w passes beside everything the map holds.
        bool blocked = false;
        if (all(lessThanEqual(abs(q.xy), vec2(1.0)))) {
            float occluder =
                texelFetch(skyMaps, skyMapTexel(q.xy, k, maps.tile.z, maps.tile.w), 0).r;
            // How far toward the sky the nearest surface in this direction lies.
            blocked = (q.z - occluder) * diameter > aoReach;
        }
        blocked = blocked || blockedExactly(p, w, aoReach);
        open += weight;
        arriving += blocked ? vec3(0.0) : weight;
    }
    return mix(vec3(1.0), arriving / max(open, vec3(1e-20)), greaterThan(open, vec3(0.0)));
}

#endif
