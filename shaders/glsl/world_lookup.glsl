// The bounce at a surface point, looked up in the world cache (world_cache.glsl): world.lookup's
// value at each of its pixels, and world.lookup_edges' at a pixel no half-resolution sample
// stands for. The value is interpolated between the eight cells around the point at the level
// world.insert took (its own, or one coarser or finer where its own cell is absent) and with its
// normal's direction, trilinearly by the point's place between their centres, so that no cell's
// edge shows; a cell absent or still empty drops out of the weights. Each cell's value is carried
// over from its own normal to the point's by its light's directional estimate (toNormal). Where
// the cells hold the sky's visibility too (SKY: world_sky_visibility.comp), it is interpolated
// with the same weights. The debug views (WORLD_VIEW_*) show the point's own cell instead.
// Needs: frame, constants (WorldConstants), common.glsl, world_cache.glsl, the constant SKY, and
// the samplers worldKeys, worldIrradiance, worldUsed, worldPoints, worldDirections, worldSky
// (world.sky, read where SKY).
#ifndef SSGI_WORLD_LOOKUP_GLSL
#define SSGI_WORLD_LOOKUP_GLSL

uint worldKeyAt(ivec2 e) {
    return texelFetch(worldKeys, e, 0).r;
}
float worldSamplesAt(ivec2 e) {
    return texelFetch(worldIrradiance, e, 0).a;
}

// What carries a cell's value over to normal n: the ratio of its light's directional estimate
// for n to that for the cell's own normal (world_gather.comp), at most 4.
float toNormal(ivec2 entry, vec3 n) {
    vec4 d = texelFetch(worldDirections, entry, 0);
    vec3 own = unpackCellNormal(texelFetch(worldPoints, entry, 0).w);
    float there = d.x * 0.25 + 0.5 * dot(d.yzw, own);
    float here = d.x * 0.25 + 0.5 * dot(d.yzw, n);
    return there > 0.0 ? clamp(here / there, 0.0, 4.0) : 1.0;
}

// What the lookup writes at the surface point p with normal n: the bounce (irradiance / pi), or
// for a debug view, the point's own cell; and in `sky`, where SKY, the sky's visibility (1
// where no cell holds it, and in the debug views).
vec4 worldLookup(vec3 p, vec3 n, int view, out vec4 sky) {
    sky = vec4(1.0);
    int level = worldLevel(distance(p, frame.cameraPosition.xyz));
    int direction = worldDirection(n);
    // The cell and level world.insert took (world_cache.glsl).
    ivec2 own = findPixelCell(p, level, direction);
    if (view != WORLD_VIEW_LIGHT) {
        if (own.x < 0) return vec4(1.0, 0.0, 0.0, 1.0); // no cell: red
        vec4 cell = texelFetch(worldIrradiance, own, 0);
        float unused = float(uint(frame.patternFrame) - texelFetch(worldUsed, own, 0).r);
        return view == WORLD_VIEW_CELLS
                   ? vec4(cell.rgb, 1.0)
                   : vec4(cell.a == 0.0 ? 1.0 : 0.0, cell.a / constants.cells.z,
                          min(unused / float(constants.table.z), 1.0), 1.0);
    }
    // The point's place among the centres of the cells around it.
    vec3 u = p / worldCellSide(level) - 0.5;
    ivec3 base = ivec3(floor(u));
    vec3 f = u - vec3(base);
    vec3 sum = vec3(0.0), skySum = vec3(0.0);
    float weights = 0.0;
    // The layer of cells along the normal's axis that holds the point first, then the other,
    // each from the corner nearest the point. A surface across that axis (a floor, a wall) has
    // cells in one layer only: where the other's nearest corner is absent, so are its others
    // (but where the surface ends at a layer's edge), and its lookups are left out.
    int axis = direction / 2;
    ivec3 nearest = ivec3(greaterThanEqual(f, vec3(0.5)));
    for (int corner = 0; corner < 8; ++corner) {
        ivec3 offset;
        offset[axis] = corner >> 2;
        offset[(axis + 1) % 3] = corner & 1;
        offset[(axis + 2) % 3] = (corner >> 1) & 1;
        offset ^= nearest;
        ivec2 entry = corner == 0 ? own : findCell(worldKey(base + offset, level, direction));
        if (entry.x < 0) {
            if (corner == 4) break;
            continue;
        }
        vec4 cell = texelFetch(worldIrradiance, entry, 0);
        if (cell.a == 0.0) continue;
        vec3 w3 = mix(1.0 - f, f, vec3(offset));
        float w = w3.x * w3.y * w3.z;
        sum += cell.rgb * w * toNormal(entry, n);
        if (SKY) skySum += texelFetch(worldSky, entry, 0).rgb * w;
        weights += w;
    }
    if (SKY && weights > 0.0) sky = vec4(skySum / weights, 1.0);
    return vec4(weights > 0.0 ? sum / weights : vec3(0.0), 1.0);
}

#endif
