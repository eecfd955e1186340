// The Lambertian albedo (rgb, linear) and coverage (a, for the alpha mask) of the surface a draw
// rasterises, as scene.h's Material says: baseColorFactor x base-colour texture x vertex colour.
// Included after the DrawBlock and the baseColorTexture binding it reads.

vec4 baseColor(vec2 uv, vec4 vertexColor) {
    vec4 color = draw.baseColorFactor;
    if (draw.material.x > 0.5) color *= texture(baseColorTexture, uv);
    if (draw.material.z > 0.5) color *= vertexColor;
    return color;
}
