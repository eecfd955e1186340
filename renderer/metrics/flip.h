// LDR-FLIP (Andersson, Nilsson, Akenine-Möller, Oskarsson, Åström, Fairchild 2020, "FLIP: A
// Difference Evaluator for Alternating Images", HPG 2020): a per-pixel estimate, in [0, 1], of
// how visible the difference between two display images is to an observer flipping between
// them at a given viewing distance. Written from the paper's equations; the steps are exposed
// so that the tests can check them against values computed by hand.
#pragma once

#include "metrics/metrics.h"

#include <glm/glm.hpp>

#include <vector>

namespace ssgi::metrics::flip {

// Pixels per degree of visual angle. The paper's default: a 0.7 m wide 3840-pixel monitor seen
// from 0.7 m, 0.7 * (3840 / 0.7) * pi / 180 = 67.02.
constexpr double kDefaultPpd = 67.0;

// The paper's constants: colour-error exponent and redistribution (cutoff p_c of the maximum
// error maps to p_t), feature-error exponent, and the feature detectors' width in degrees.
constexpr double kQc = 0.7, kPc = 0.4, kPt = 0.95, kQf = 0.5, kFeatureWidth = 0.082;

struct Result {
    double mean = 0.0;       // mean of `map` over the image
    std::vector<double> map; // per pixel, rows top to bottom
};

// FLIP of `test` against `reference`, both display-encoded sRGB in [0, 1] (values outside are
// clamped; NaN stays NaN and spreads to the neighbours the filters reach). Throws
// std::invalid_argument when the sizes differ or ppd is not positive.
Result flip(const Image& test, const Image& reference, double ppd = kDefaultPpd);

// --- The colour pipeline, one step at a time. ---

glm::dvec3 linearFromSrgb(glm::dvec3 srgb);
// The linearized opponent space of Zhang and Wandell: Y = 116 y - 16, Cx = 500 (x - y),
// Cz = 200 (y - z), with x, y, z the CIE XYZ of the colour relative to linear white (1, 1, 1).
glm::dvec3 ycxczFromLinear(glm::dvec3 rgb);
glm::dvec3 linearFromYcxcz(glm::dvec3 ycxcz);
// CIE L*a*b* with the same white.
glm::dvec3 labFromLinear(glm::dvec3 rgb);
// The Hunt effect (colourfulness rises with luminance): a and b scaled by 0.01 L.
glm::dvec3 hunt(glm::dvec3 lab);
// HyAB (Abasi et al. 2020): |L1 - L2| + the Euclidean distance in the (a, b) plane.
double hyab(glm::dvec3 lab1, glm::dvec3 lab2);
// The largest colour error, HyAB of Hunt-adjusted green and blue, raised to q_c.
double maxColorError();
// HyAB distance -> colour error in [0, 1]: d^q_c below p_c of the maximum rises linearly to p_t,
// the rest of the range is compressed into [p_t, 1].
double redistributeColorError(double hyabDistance);
// Radius in pixels of the CSF filters at `ppd`: three standard deviations of the widest
// Gaussian of the paper's Table 1 (b = 0.04, the blue-yellow channel's).
int csfRadius(double ppd);

// --- The feature pipeline. ---

// Feature error from the edge and point responses' magnitudes of the two images:
// (max(|edges difference|, |points difference|) / sqrt 2)^q_f.
double featureError(double edgeTest, double edgeReference, double pointTest, double pointReference);

// RGBA ready for writeImage(.png): the FLIP map on the project's error ramp (errorColor, linear
// in FLIP: black 0, pale yellow 1), cyan where the value is not finite.
std::vector<float> flipErrorMap(const std::vector<double>& map);

} // namespace ssgi::metrics::flip
