#version 460
// Ceiling probe: the memory bandwidth a trivial kernel reaches: each pixel reads one RGBA32F
// texel and writes one (32 bytes a pixel), on images far larger than any cache.
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform sampler2D source;
layout(set = 0, binding = 1, rgba32f) uniform writeonly image2D target;
layout(push_constant) uniform ProbeBlock { ivec4 size; }; // xy: image size

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, size.xy))) return;
    imageStore(target, pixel, texelFetch(source, pixel, 0) * 0.5 + 1.0);
}
