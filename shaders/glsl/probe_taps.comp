#version 460
// Ceiling probe: how many texel fetches per second the device makes when a kernel does almost
// nothing else. Each pixel fetches TAPS texels of an RGBA32F image (the G-buffer's and the RSM's
// position format) and writes their mean. SPREAD > 0 keeps the taps within a window of
// 2 SPREAD texels around the pixel (the locality of an AO or PCF kernel); SPREAD = 0 scatters
// them over the whole source (the locality of a VPL gather over the RSM). The coordinates come
// from an integer LCG so that the ALU per tap stays far below any real pass's.
layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const int TAPS = 64;
layout(constant_id = 1) const int SPREAD = 32; // a power of two, or 0

layout(set = 0, binding = 0) uniform sampler2D source;
layout(set = 0, binding = 1, rgba16f) uniform writeonly image2D target;
// xy: target size; zw: source size (powers of two).
layout(push_constant) uniform ProbeBlock { ivec4 size; };

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, size.xy))) return;
    ivec2 home = pixel * size.zw / size.xy;
    uint state = (uint(pixel.x) * 73856093u) ^ (uint(pixel.y) * 19349663u);
    vec4 sum = vec4(0.0);
    for (int i = 0; i < TAPS; ++i) {
        state = state * 1664525u + 1013904223u;
        ivec2 bits = ivec2(int(state >> 16), int(state & 0xffffu));
        ivec2 texel = SPREAD > 0 ? home + (bits & (2 * SPREAD - 1)) - SPREAD : bits & (size.zw - 1);
        sum += texelFetch(source, clamp(texel, ivec2(0), size.zw - 1), 0);
    }
    imageStore(target, pixel, sum / float(TAPS));
}
