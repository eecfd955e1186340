#version 460
// Ceiling probe, setup: fills a source image with values that differ from texel to texel, so
// that no fetch of the probe kernels can be folded away by the compiler.
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba32f) uniform writeonly image2D target;
layout(push_constant) uniform ProbeBlock { ivec4 size; }; // xy: target size

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, size.xy))) return;
    imageStore(target, pixel, vec4(vec2(pixel), float(pixel.x ^ pixel.y), 1.0));
}
