// Sky visibility maps: where direction k of K lies, and where a world point falls in map k.
// Shared by the raster pass that draws the maps (sky_depth.vert) and the lookup
// (sky_visibility.comp), so both use the same directions and projections.

// Direction k of K, spread evenly over the whole sphere (a Fibonacci lattice: equal areas,
// 4 pi / K steradians each), pointing from the scene toward the sky.
vec3 skyMapDirection(int k, int count) {
    float y = 1.0 - (2.0 * float(k) + 1.0) / float(count);
    float r = sqrt(max(1.0 - y * y, 0.0));
    float phi = 2.39996322972865 * float(k); // the golden angle
    return vec3(r * cos(phi), y, r * sin(phi));
}

// A world point in map k, seen from outside the bounding sphere looking along -direction:
// xy in [-1, 1] across the sphere, z in [0, 1] from the sky side (0) to the far side (1).
vec3 skyMapProject(vec3 world, vec3 direction, vec4 sphere) {
    vec3 up = abs(direction.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
    vec3 right = normalize(cross(up, direction));
    vec3 down = cross(direction, right);
    vec3 d = world - sphere.xyz;
    return vec3(dot(d, right) / sphere.w, dot(d, down) / sphere.w,
                (sphere.w - dot(d, direction)) / (2.0 * sphere.w));
}

// The atlas texel of a projected point in map k (tiles of `size` texels, `perRow` a row).
ivec2 skyMapTexel(vec2 projected, int k, int perRow, int size) {
    ivec2 inTile = clamp(ivec2((projected * 0.5 + 0.5) * float(size)), ivec2(0), ivec2(size - 1));
    return ivec2(k % perRow, k / perRow) * size + inTile;
}
