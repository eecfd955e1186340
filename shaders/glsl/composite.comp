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
layout(constant_id = 3) const int HAS_SKY_VISIBILITY = 0;
layout(constant_id = 4) const int HAS_CONTACT = 0; // shadowImage is the contact pass's (r, g)

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform sampler2D gbufferViewDepth;
layout(set = 0, binding = 2) uniform sampler2D gbufferNormal;
layout(set = 0, binding = 3) uniform sampler2D gbufferAlbedo;
layout(set = 0, binding = 4) uniform sampler2D directRadiance;
layout(set = 0, binding = 5) uniform sampler2D shadowImage;
layout(set = 0, binding = 6) uniform sampler2D aoImage;
layout(set = 0, binding = 7) uniform sampler2D indirectImage; // irradiance / pi
layout(set = 0, binding = 8) uniform sampler2D ssdoImage;     // radiance
layout(set = 0, binding = 9) uniform usampler2D rsmVpls; // rsm_vpl.glsl
layout(set = 0, binding = 10) uniform sampler2D secondLayer; // depth peeling's position
layout(set = 0, binding = 11) uniform sampler2D skyVisibilityImage; // beyond the AO's radius
layout(set = 0, binding = 12, rgba32f) uniform writeonly image2D hdrImage;
layout(set = 0, binding = 13, rgba8) uniform writeonly image2D ldrImage;
layout(push_constant) uniform CompositeBlock { CompositeConstants constants; };

#include "gbuffer_position.glsl"
#include "rsm_vpl.glsl"

// The display transform of shared.h, channel by channel.
vec3 tonemap(vec3 x) {
    return vec3(tonemapAces(x.r), tonemapAces(x.g), tonemapAces(x.b));
}
vec3 encodeSrgb(vec3 linear) {
    return vec3(encodeSrgb(linear.r), encodeSrgb(linear.g), encodeSrgb(linear.b));
}

// Irradiance/pi from an unoccluded sky on a surface with normal n (closed form, common.glsl);
// the AO then stands for the sky's visibility.
vec3 skyLight(vec3 n) {
    return skyIrradianceOverPi(n, frame.skyZenith.rgb, frame.skyHorizon.rgb, frame.skyGround.rgb);
}

void main() {
    loadPixelToWorld(); // pixel_to_world.glsl
    // `written` in the images written, `pixel` in the screen images read (guard band added).
    ivec2 written = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(written, imageSize(hdrImage)))) return;
    ivec2 pixel = written + constants.guardBand;
    vec2 uv = (vec2(pixel) + 0.5) * frame.viewport.zw;
    vec4 position = gbufferPosition(pixel);
    vec3 n = texelFetch(gbufferNormal, pixel, 0).xyz;
    vec3 albedo = texelFetch(gbufferAlbedo, pixel, 0).rgb;
    vec3 direct = texelFetch(directRadiance, pixel, 0).rgb;
    float ao = HAS_AO != 0 ? texelFetch(aoImage, pixel, 0).r : 1.0;
    vec3 indirect = HAS_INDIRECT != 0 ? albedo * texelFetch(indirectImage, pixel, 0).rgb : vec3(0);
    vec3 ssdo = HAS_SSDO != 0 ? texelFetch(ssdoImage, pixel, 0).rgb : vec3(0.0);
    vec3 skyVisibility =
        HAS_SKY_VISIBILITY != 0 ? texelFetch(skyVisibilityImage, pixel, 0).rgb : vec3(1.0);

    vec3 hdr;
    if (position.w == 0.0) {
        vec4 far = frame.inverseViewProjection * vec4(uv * 2.0 - 1.0, 1.0, 1.0);
        vec3 dir = normalize(far.xyz / far.w - frame.cameraPosition.xyz);
        hdr = skyRadiance(dir, frame.skyZenith.rgb, frame.skyHorizon.rgb, frame.skyGround.rgb);
    } else {
        vec3 sky = HAS_SSDO != 0 ? ssdo : albedo * skyLight(n) * ao * skyVisibility;
        hdr = direct + sky + indirect;
    }
    // Every radiance above is in the intermediate images' units (see radianceScale).
    float unit = frame.radianceScale.x;
    hdr *= unit;

    // A debug view replaces both outputs: the EXR holds the view's linear quantity (radiance,
    // visibility, normal, distance), the PNG its display encoding.
    float exposure = frame.exposure;
    vec3 value = hdr;
    int view = constants.view;
    if (view == VIEW_ALBEDO) value = albedo;
    if (view == VIEW_NORMAL) value = position.w == 0.0 ? vec3(0.0) : n;
    if (view == VIEW_DEPTH)
        value = vec3(position.w == 0.0 ? 0.0 : distance(position.xyz, frame.cameraPosition.xyz));
    if (view == VIEW_DIRECT) value = direct * unit;
    float texel = 2.0 * frame.lightFrustum.z / frame.lightFrustum.w;
    vec2 outputUv = (vec2(written) + 0.5) / vec2(imageSize(hdrImage)); // the light's views fill it
    if (view == VIEW_RSM_FLUX || view == VIEW_RSM_NORMAL) { // read only for their views
        uvec4 vpl = texelFetch(rsmVpls, ivec2(outputUv * vec2(textureSize(rsmVpls, 0))), 0);
        if (view == VIEW_RSM_FLUX) value = rsmTexelFlux(vpl) * unit / (texel * texel);
        if (view == VIEW_RSM_NORMAL) value = rsmTexelDrawn(vpl) ? rsmTexelNormal(vpl) : vec3(0.0);
    }
    vec4 shadow = texelFetch(shadowImage, pixel, 0);
    if (view == VIEW_SHADOW) value = vec3(shadow.r);
    if (view == VIEW_AO) value = vec3(ao);
    if (view == VIEW_INDIRECT) value = indirect * unit;
    if (view == VIEW_SSDO) value = ssdo * unit;
    if (view == VIEW_SKY_VISIBILITY) value = skyVisibility;
    // The contact pass keeps the shadow map's term in g: what contact shadows took away (the
    // shadow's own history holds its blur in g: without contact shadows, nothing taken away).
    float mapped = HAS_CONTACT != 0 ? shadow.g : shadow.r;
    if (view == VIEW_CONTACT) value = vec3(shadow.r, max(mapped - shadow.r, 0.0), 0.0);
    if (view == VIEW_PEEL) {
        vec4 second = texelFetch(secondLayer, pixel, 0);
        value = vec3(second.w == 0.0 ? 0.0 : distance(second.xyz, frame.cameraPosition.xyz));
    }

    vec3 shown = tonemap(value * exposure);
    if (view == VIEW_NORMAL || view == VIEW_RSM_NORMAL)
        shown = position.w == 0.0 && view == VIEW_NORMAL ? vec3(0.0) : value * 0.5 + 0.5;
    if (view == VIEW_DEPTH || view == VIEW_PEEL)
        shown = vec3(value.x == 0.0 ? 0.0 : max(1.0 - value.x / frame.sceneDiagonal, 0.0));
    if (view == VIEW_RSM_FLUX) shown = tonemap(value * exposure * 0.3);
    if (view == VIEW_SHADOW || view == VIEW_AO || view == VIEW_SKY_VISIBILITY) shown = value;
    // Lit white, shadowed black, and in red what contact shadows darkened.
    if (view == VIEW_CONTACT) shown = mix(vec3(value.x), vec3(1.0, 0.0, 0.0), value.y);
    // Colours are encoded for display; normals, depth and visibilities are data, shown as is.
    bool isData = view == VIEW_NORMAL || view == VIEW_RSM_NORMAL || view == VIEW_DEPTH ||
                  view == VIEW_SHADOW || view == VIEW_AO || view == VIEW_PEEL ||
                  view == VIEW_CONTACT || view == VIEW_SKY_VISIBILITY;
    imageStore(hdrImage, written, vec4(view == VIEW_FINAL ? hdr : value, 1.0));
    imageStore(ldrImage, written, vec4(isData ? shown : encodeSrgb(shown), 1.0));
}
