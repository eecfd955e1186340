#version 460
#extension GL_GOOGLE_include_directive : require
// Composite: direct light + sky light (occluded by AO, or SSDO's directional occlusion and
// bounce in its place) + one-bounce indirect light, the sky itself where no geometry is; then
// exposure, tonemap and sRGB encoding. Or any intermediate image instead (debug views).
#include "shared.h"
#include "common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const int HAS_AO = 0;
layout(constant_id = 1) const int HAS_INDIRECT = 0;
layout(constant_id = 2) const int HAS_SSDO = 0;

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform sampler2D gbufferPosition;
layout(set = 0, binding = 2) uniform sampler2D gbufferNormal;
layout(set = 0, binding = 3) uniform sampler2D gbufferAlbedo;
layout(set = 0, binding = 4) uniform sampler2D directRadiance;
layout(set = 0, binding = 5) uniform sampler2D shadowImage;
layout(set = 0, binding = 6) uniform sampler2D aoImage;
layout(set = 0, binding = 7) uniform sampler2D indirectImage; // irradiance / pi
layout(set = 0, binding = 8) uniform sampler2D ssdoImage;     // radiance
layout(set = 0, binding = 9) uniform sampler2D rsmFlux;
layout(set = 0, binding = 10) uniform sampler2D rsmNormal;
layout(set = 0, binding = 11, rgba32f) uniform writeonly image2D hdrImage;
layout(set = 0, binding = 12, rgba8) uniform writeonly image2D ldrImage;
layout(push_constant) uniform CompositeBlock { CompositeConstants constants; };

// Narkowicz's fit of the ACES filmic curve.
vec3 tonemap(vec3 x) {
    return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

vec3 encodeSrgb(vec3 linear) {
    return mix(linear * 12.92, 1.055 * pow(linear, vec3(1.0 / 2.4)) - 0.055,
               step(vec3(0.0031308), linear));
}

// Irradiance/pi from an unoccluded sky on a surface with normal n: the gradient evaluated along
// the normal is exact for a constant sky and a fair estimate for a smooth gradient.
vec3 skyLight(vec3 n) {
    return skyRadiance(n, frame.skyZenith.rgb, frame.skyHorizon.rgb, frame.skyGround.rgb);
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, ivec2(frame.viewport.xy)))) return;
    vec2 uv = (vec2(pixel) + 0.5) * frame.viewport.zw;
    vec4 position = texelFetch(gbufferPosition, pixel, 0);
    vec3 n = texelFetch(gbufferNormal, pixel, 0).xyz;
    vec3 albedo = texelFetch(gbufferAlbedo, pixel, 0).rgb;
    vec3 direct = texelFetch(directRadiance, pixel, 0).rgb;
    float ao = HAS_AO != 0 ? texelFetch(aoImage, pixel, 0).r : 1.0;
    vec3 indirect = HAS_INDIRECT != 0 ? albedo * texelFetch(indirectImage, pixel, 0).rgb : vec3(0);
    vec3 ssdo = HAS_SSDO != 0 ? texelFetch(ssdoImage, pixel, 0).rgb : vec3(0.0);

    vec3 hdr;
    if (position.w == 0.0) {
        vec4 far = frame.inverseViewProjection * vec4(uv * 2.0 - 1.0, 1.0, 1.0);
        vec3 dir = normalize(far.xyz / far.w - frame.cameraPosition.xyz);
        hdr = skyRadiance(dir, frame.skyZenith.rgb, frame.skyHorizon.rgb, frame.skyGround.rgb);
    } else {
        vec3 sky = HAS_SSDO != 0 ? ssdo : albedo * skyLight(n) * ao;
        hdr = direct + sky + indirect;
    }

    float exposure = frame.params.x;
    vec3 shown = tonemap(hdr * exposure);
    int view = constants.mode.x;
    if (view == VIEW_ALBEDO) shown = albedo;
    if (view == VIEW_NORMAL) shown = position.w == 0.0 ? vec3(0.0) : n * 0.5 + 0.5;
    if (view == VIEW_DEPTH) {
        float d = position.w == 0.0 ? 0.0 : distance(position.xyz, frame.cameraPosition.xyz);
        shown = vec3(d == 0.0 ? 0.0 : max(1.0 - d / frame.params.w, 0.0));
    }
    if (view == VIEW_DIRECT) shown = tonemap(direct * exposure);
    if (view == VIEW_RSM_FLUX) {
        vec3 flux = texture(rsmFlux, uv).rgb;
        float texel = 2.0 * frame.lightFrustum.z / frame.lightFrustum.w;
        shown = tonemap(flux / (texel * texel) * exposure * 0.3);
    }
    if (view == VIEW_RSM_NORMAL) shown = texture(rsmNormal, uv).xyz * 0.5 + 0.5;
    if (view == VIEW_SHADOW) shown = vec3(texelFetch(shadowImage, pixel, 0).r);
    if (view == VIEW_AO) shown = vec3(ao);
    if (view == VIEW_INDIRECT) shown = tonemap(indirect * exposure);
    if (view == VIEW_SSDO) shown = tonemap(ssdo * exposure);
    // Colours are encoded for display; normals, depth and visibilities are data, shown as is.
    bool isData = view == VIEW_NORMAL || view == VIEW_RSM_NORMAL || view == VIEW_DEPTH ||
                  view == VIEW_SHADOW || view == VIEW_AO;
    imageStore(hdrImage, pixel, vec4(hdr, 1.0));
    imageStore(ldrImage, pixel, vec4(isData ? shown : encodeSrgb(shown), 1.0));
}
