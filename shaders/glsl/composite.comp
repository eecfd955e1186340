#version 460
#extension GL_GOOGLE_include_directive : require
// Composite: direct light + sky light + the lighting terms the passes hand it, each by its
// role (TERM_* of shared.h: the AO and the sky's visibility occlude the sky light, SSDO's
// radiance replaces it, the bounce's irradiance is added), the sky itself where no geometry is;
// then exposure, tonemap and sRGB encoding. Or any intermediate image instead (debug views).
#include "shared.h"
#include "common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const int HAS_CONTACT = 0; // shadowImage is the contact pass's (r, g)
// The role of each term slot (TERM_*), in the order the terms are added up.
layout(constant_id = 1) const int TERM0_ROLE = TERM_NONE;
layout(constant_id = 2) const int TERM1_ROLE = TERM_NONE;
layout(constant_id = 3) const int TERM2_ROLE = TERM_NONE;
layout(constant_id = 4) const int TERM3_ROLE = TERM_NONE;

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform sampler2D gbufferViewDepth;
layout(set = 0, binding = 2) uniform sampler2D gbufferNormal;
layout(set = 0, binding = 3) uniform sampler2D gbufferAlbedo;
layout(set = 0, binding = 4) uniform sampler2D directRadiance;
layout(set = 0, binding = 5) uniform sampler2D shadowImage;
layout(set = 0, binding = 6) uniform usampler2D rsmVpls; // rsm_vpl.glsl
layout(set = 0, binding = 7) uniform sampler2D secondLayer; // depth peeling's position
layout(set = 0, binding = 8) uniform sampler2D term0;
layout(set = 0, binding = 9) uniform sampler2D term1;
layout(set = 0, binding = 10) uniform sampler2D term2;
layout(set = 0, binding = 11) uniform sampler2D term3;
layout(set = 0, binding = 12, rg32ui) uniform writeonly uimage2D hdrImage; // packHdr
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

bool occludesSky(int role) {
    return role == TERM_SKY_OCCLUSION || role == TERM_SKY_FILTER;
}
// The fraction of the sky's light a TERM_SKY_OCCLUSION term lets through: the AO is stored
// unclamped, for the cache's mean (ao.comp), and used clamped at 1.
float letThrough(vec4 term) {
    return min(term.r, 1.0);
}
// What a term does to the sky light, and to the light added to it.
void occludeSky(int role, vec4 term, inout vec3 sky) {
    if (role == TERM_SKY_OCCLUSION) sky *= letThrough(term);
    if (role == TERM_SKY_FILTER) sky *= term.rgb;
    if (role == TERM_SKY_RADIANCE) sky = term.rgb;
}
void addLight(int role, vec4 term, vec3 albedo, inout vec3 hdr) {
    if (role == TERM_IRRADIANCE) hdr += albedo * term.rgb;
}

// The HDR output's texel (shared.h hdrBits).
uvec2 packHdr(vec3 v) {
    uvec3 b = uvec3(hdrBits(v.r), hdrBits(v.g), hdrBits(v.b));
    return uvec2(b.r | (b.g << 21), (b.g >> 11) | (b.b << 10));
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
    // Each slot's term, read only where the slot has one.
    vec4 t0 = TERM0_ROLE != TERM_NONE ? texelFetch(term0, pixel, 0) : vec4(0.0);
    vec4 t1 = TERM1_ROLE != TERM_NONE ? texelFetch(term1, pixel, 0) : vec4(0.0);
    vec4 t2 = TERM2_ROLE != TERM_NONE ? texelFetch(term2, pixel, 0) : vec4(0.0);
    vec4 t3 = TERM3_ROLE != TERM_NONE ? texelFetch(term3, pixel, 0) : vec4(0.0);

    vec3 hdr;
    if (position.w == 0.0) {
        vec4 far = frame.inverseViewProjection * vec4(uv * 2.0 - 1.0, 1.0, 1.0);
        vec3 dir = normalize(far.xyz / far.w - frame.cameraPosition.xyz);
        hdr = skyRadiance(dir, frame.skyZenith.rgb, frame.skyHorizon.rgb, frame.skyGround.rgb);
    } else {
        // The sky light, occluded or replaced by its terms, then the light the others add.
        vec3 sky = albedo * skyLight(n);
        occludeSky(TERM0_ROLE, t0, sky);
        occludeSky(TERM1_ROLE, t1, sky);
        occludeSky(TERM2_ROLE, t2, sky);
        occludeSky(TERM3_ROLE, t3, sky);
        hdr = direct + sky;
        addLight(TERM0_ROLE, t0, albedo, hdr);
        addLight(TERM1_ROLE, t1, albedo, hdr);
        addLight(TERM2_ROLE, t2, albedo, hdr);
        addLight(TERM3_ROLE, t3, albedo, hdr);
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
    // A term's view: what it lets through of the sky, or the radiance it adds (an occluder the
    // frame does not have lets everything through, a light it does not have adds nothing).
    int role = constants.termRole;
    bool termIsData = view == VIEW_TERM && occludesSky(role);
    if (view == VIEW_TERM) {
        int slot = constants.termSlot;
        vec4 term = slot == 0 ? t0 : slot == 1 ? t1 : slot == 2 ? t2 : slot == 3 ? t3
                  : vec4(occludesSky(role) ? 1.0 : 0.0);
        if (role == TERM_SKY_OCCLUSION) value = vec3(letThrough(term));
        if (role == TERM_SKY_FILTER) value = term.rgb;
        if (role == TERM_SKY_RADIANCE) value = term.rgb * unit;
        if (role == TERM_IRRADIANCE) value = albedo * term.rgb * unit;
    }
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
    if (view == VIEW_SHADOW || termIsData) shown = value;
    // Lit white, shadowed black, and in red what contact shadows darkened.
    if (view == VIEW_CONTACT) shown = mix(vec3(value.x), vec3(1.0, 0.0, 0.0), value.y);
    // Colours are encoded for display; normals, depth and visibilities are data, shown as is.
    bool isData = view == VIEW_NORMAL || view == VIEW_RSM_NORMAL || view == VIEW_DEPTH ||
                  view == VIEW_SHADOW || view == VIEW_PEEL || view == VIEW_CONTACT || termIsData;
    imageStore(hdrImage, written, uvec4(packHdr(view == VIEW_FINAL ? hdr : value), 0u, 0u));
    imageStore(ldrImage, written, vec4(isData ? shown : encodeSrgb(shown), 1.0));
}
