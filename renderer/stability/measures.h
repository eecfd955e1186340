// The stability measures on the CPU, over images read back from the renderer (RGBA floats, rows
// top to bottom): error inside a mask, frame-to-frame change (flicker), stale lighting, the
// NaN/Inf count, and the masks of the places where screen-space methods fail (measures.cpp),
// in the stability library that the `stability` command and its tests share.
#pragma once

#include "metrics/metrics.h"
#include "scene/camera.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace ssgi::stability {

using metrics::Mask;
using Pixels = std::vector<float>;

// What the measures read of one rendered frame.
struct View {
    uint32_t width = 0, height = 0;
    Camera camera;
    Pixels hdr, position, normal, albedo;
    size_t pixels() const { return size_t(width) * height; }
    // Luminance of the radiance over the albedo: the lighting, without the texture, which would
    // swamp any change of it wherever a pixel lands a fraction of a texel away.
    double lighting(size_t i) const {
        constexpr double weight[3] = {0.2126, 0.7152, 0.0722}; // Rec. 709 luminance
        double l = 0.0;
        for (size_t c = 0; c < 3; ++c)
            l += weight[c] * hdr[4 * i + c] / std::max(albedo[4 * i + c], 0.02f);
        return l;
    }
    bool geometry(size_t i) const { return position[4 * i + 3] != 0.0f; }
    glm::vec3 world(size_t i) const {
        return {position[4 * i], position[4 * i + 1], position[4 * i + 2]};
    }
    float distance(size_t i) const { return glm::distance(world(i), camera.position); }
};

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

size_t countNonFinite(const Pixels& rgba);

double luminance(const Pixels& rgba, size_t i);

Mask geometryMask(const View& v);

Mask subtract(Mask a, const Mask& b);

// relMSE (metrics.h) of `test` against `reference` inside `mask`; NaN for an empty mask.
double maskedRelMse(const Pixels& test, const Pixels& reference, const Mask& mask);

glm::mat4 viewProjection(const View& v);

// Where `before` shows the world point of pixel `i` of `now`: the pixel nearest its projection
// and the 3x3 around it, which a surface seen at a slant may need.
struct Lookup {
    bool onScreen = false;
    long x = 0, y = 0;
};
Lookup lookup(const View& before, const glm::mat4& viewProjection, glm::vec3 p);

// The pixel of `before` that saw the same surface point as pixel `i` of `now` (within 3% of
// its distance to the camera), or -1 where none did.
long correspondingPixel(const View& before, const glm::mat4& viewProjection, const View& now,
                        size_t i);

// Whether `before` could not see the world point of pixel `i` of `now` though it lies on its
// screen: every pixel around its projection shows a surface nearer the camera (by 2%: depth
// quantisation).
bool hiddenBefore(const View& before, const glm::mat4& viewProjection, const View& now, size_t i);

// Pixels of `now` whose surface `before` could not see though it was on its screen: revealed
// from behind an occluder (surfaces entering at the screen edge are not counted).
Mask disoccludedMask(const View& before, const View& now);

// Pixels of `now` whose surface `before` could not have seen: off its screen, or hidden there
// behind a nearer surface (hiddenBefore(); the benefit of the doubt at silhouettes).
Mask unseenMask(const View& before, const View& now);

// Mean absolute change of the lighting (View::lighting) from `before` to `now` over the mask's
// pixels, relative to its mean. When the camera moved, each pixel is compared with the pixel
// that saw the same surface point before (a Lambertian surface under a still light looks the
// same from anywhere); pixels no one saw before are left out.
double flicker(const View& before, const View& now, const Mask& mask);

// How much of the old lighting remains: the residual to the new converged image projected on
// the old-to-new change, sum (a - new)(old - new) / sum (old - new)^2 over the mask, in
// luminance. 1: the image still shows the old lighting; 0: none of it (noise averages out).
double staleFraction(const Pixels& image, const Pixels& oldImage, const Pixels& newImage,
                     const Mask& mask);

// Pixels whose luminance differs between two images by more than `relative` of their mean.
Mask changedMask(const Pixels& a, const Pixels& b, const Mask& within, double relative);

// Pixels seen at a grazing angle: |n . v| below `cosine`.
Mask grazingMask(const View& v, float cosine);

// Distance to the camera, +inf where there is no geometry (the sky is the farthest of all).
std::vector<float> distances(const View& v);

Mask dilate(const Mask& m, uint32_t width, uint32_t height, int radius);

// Thin geometry: runs of at most `maxWidth` pixels, horizontal or vertical, with something at
// least `ratio` times farther on both sides; dilated by `border` pixels to take in the
// background right beside them, where screen-space occlusion and the history go wrong.
Mask thinMask(const View& v, int maxWidth, float ratio, int border);

// Depth discontinuities: pixels within `band` pixels of a neighbour whose distance differs by
// more than `ratio`, on both sides of the edge (where halos form).
Mask depthEdgeMask(const View& v, float ratio, int band);

// Pixels whose surface lies within `reach` of the box but not on it: the receivers of the
// occlusion and bounce light a box gives.
Mask nearBoxMask(const View& v, const Aabb& box, float reach);

// Frames (1 = the first) from which every later value stays within `tolerance`; -1 if the
// last does not.
int framesUntilWithin(const std::vector<double>& errors, double tolerance);

} // namespace ssgi::stability
