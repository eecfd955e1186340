#include "metrics/flip.h"

#include "metrics/error_map.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace ssgi::metrics::flip {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Linear sRGB (D65) to CIE XYZ. glm fills columns first, hence the transpose: the rows below
// are the matrix's rows.
const glm::dmat3& xyzFromRgb() {
    static const glm::dmat3 m =
        glm::transpose(glm::dmat3(0.4124564, 0.3575761, 0.1804375, 0.2126729, 0.7151522, 0.0721750,
                                  0.0193339, 0.1191920, 0.9503041));
    return m;
}
const glm::dmat3& rgbFromXyz() {
    static const glm::dmat3 m = glm::inverse(xyzFromRgb());
    return m;
}
// The white both opponent spaces are relative to: XYZ of linear (1, 1, 1), so that white maps
// to Y = L* = 100 exactly rather than to within the matrix's rounding.
const glm::dvec3& white() {
    static const glm::dvec3 w = xyzFromRgb() * glm::dvec3(1.0);
    return w;
}

// The paper's Table 1: each channel's CSF is a1 exp(-b1 f^2) + a2 exp(-b2 f^2) in frequency f
// (cycles per degree); a2 = 0 leaves a single Gaussian for the achromatic and red-green ones.
struct Csf {
    double a1, b1, a2, b2;
};
constexpr std::array<Csf, 3> kCsf = {{
    {1.0, 0.0047, 0.0, 1e-5},  // achromatic
    {1.0, 0.0053, 0.0, 1e-5},  // red-green
    {34.1, 0.04, 13.5, 0.025}, // blue-yellow
}};
constexpr double kWidestB = 0.04;

using Plane = std::vector<double>;

// Separable convolution, kx along rows then ky along columns. Coordinates are clamped at the
// border (the edge pixel repeats), so a kernel that sums to 1 keeps a flat image flat there.
Plane convolve(const Plane& in, uint32_t w, uint32_t h, const std::vector<double>& kx,
               const std::vector<double>& ky) {
    const long rx = long(kx.size() / 2), ry = long(ky.size() / 2);
    Plane rows(in.size()), out(in.size());
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            double sum = 0.0;
            for (long k = -rx; k <= rx; ++k)
                sum += kx[size_t(k + rx)] *
                       in[size_t(y) * w + size_t(std::clamp(long(x) + k, 0L, long(w) - 1))];
            rows[size_t(y) * w + x] = sum;
        }
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            double sum = 0.0;
            for (long k = -ry; k <= ry; ++k)
                sum += ky[size_t(k + ry)] *
                       rows[size_t(std::clamp(long(y) + k, 0L, long(h) - 1)) * w + x];
            out[size_t(y) * w + x] = sum;
        }
    return out;
}

// The CSF in the spatial domain (the paper's inverse Fourier transform of Table 1's sums):
// a sqrt(pi / b) exp(-pi^2 r^2 / b), r in degrees = pixels / ppd. Each Gaussian is separable, so
// the 2D filter is applied as one separable pass per Gaussian, the terms weighted and the whole
// normalised to sum 1 (a flat field passes unchanged).
Plane csfFilter(const Plane& in, uint32_t w, uint32_t h, int channel, double ppd) {
    const Csf& p = kCsf[size_t(channel)];
    const int r = csfRadius(ppd);
    struct Term {
        double weight;
        std::vector<double> g;
    };
    std::vector<Term> terms;
    double total = 0.0;
    for (const auto& [a, b] : {std::pair{p.a1, p.b1}, std::pair{p.a2, p.b2}}) {
        if (a == 0.0) continue;
        Term t{a * std::sqrt(kPi / b), std::vector<double>(size_t(2 * r + 1))};
        double sum = 0.0;
        for (int x = -r; x <= r; ++x) {
            const double degrees = double(x) / ppd;
            sum += t.g[size_t(x + r)] = std::exp(-kPi * kPi * degrees * degrees / b);
        }
        total += t.weight * sum * sum; // the 2D kernel's sum: (sum of g)^2 per term
        terms.push_back(std::move(t));
    }
    Plane out(in.size(), 0.0);
    for (const Term& t : terms) {
        const Plane filtered = convolve(in, w, h, t.g, t.g);
        for (size_t i = 0; i < out.size(); ++i)
            out[i] += t.weight / total * filtered[i];
    }
    return out;
}

// The feature detectors' 1D factors at sigma = 0.5 w ppd: the Gaussian (sum 1), its first
// derivative (positive weights sum to 1, the negative ones to -1 by symmetry) and its second
// derivative (positive and negative weights scaled separately to 1 and -1, so that a flat or
// linear ramp gives no point response). The 2D kernels are products of these, so their
// positive and negative weights sum to 1 and -1 as the paper asks.
struct FeatureKernels {
    std::vector<double> g, d1, d2;
};
FeatureKernels featureKernels(double ppd) {
    const double sigma = 0.5 * kFeatureWidth * ppd;
    const int r = int(std::ceil(3.0 * sigma));
    FeatureKernels k{std::vector<double>(size_t(2 * r + 1)), {}, {}};
    k.d1 = k.d2 = k.g;
    double sum = 0.0, pos1 = 0.0, pos2 = 0.0, neg2 = 0.0;
    for (int x = -r; x <= r; ++x) {
        const size_t i = size_t(x + r);
        const double g = std::exp(-0.5 * x * x / (sigma * sigma));
        k.g[i] = g;
        k.d1[i] = -double(x) / (sigma * sigma) * g;
        k.d2[i] = (double(x) * x / (sigma * sigma) - 1.0) / (sigma * sigma) * g;
        sum += g;
        pos1 += std::max(k.d1[i], 0.0);
        (k.d2[i] > 0.0 ? pos2 : neg2) += k.d2[i];
    }
    for (size_t i = 0; i < k.g.size(); ++i) {
        k.g[i] /= sum;
        k.d1[i] /= pos1;
        k.d2[i] /= k.d2[i] > 0.0 ? pos2 : -neg2;
    }
    return k;
}

// One image through both pipelines: its CSF-filtered, Hunt-adjusted L*a*b* and the magnitudes
// of its edge and point responses.
struct Prepared {
    std::vector<glm::dvec3> lab;
    Plane edges, points;
};
Prepared prepare(const Image& image, double ppd, const FeatureKernels& k) {
    const uint32_t w = image.width, h = image.height;
    const size_t n = image.pixels();
    std::array<Plane, 3> opponent;
    for (Plane& p : opponent)
        p.resize(n);
    Plane achromatic(n);
    for (size_t i = 0; i < n; ++i) {
        glm::dvec3 srgb;
        for (int c = 0; c < 3; ++c) {
            const double v = image.rgba[4 * i + size_t(c)];
            srgb[c] = std::isnan(v) ? v : std::clamp(v, 0.0, 1.0);
        }
        const glm::dvec3 o = ycxczFromLinear(linearFromSrgb(srgb));
        for (int c = 0; c < 3; ++c)
            opponent[size_t(c)][i] = o[c];
        achromatic[i] = (o.x + 16.0) / 116.0; // relative luminance, 0..1, unfiltered
    }
    for (int c = 0; c < 3; ++c)
        opponent[size_t(c)] = csfFilter(opponent[size_t(c)], w, h, c, ppd);
    Prepared p;
    p.lab.resize(n);
    for (size_t i = 0; i < n; ++i) {
        // Filtering can leave the gamut; clamping keeps the error within green-to-blue's.
        const glm::dvec3 rgb =
            glm::clamp(linearFromYcxcz({opponent[0][i], opponent[1][i], opponent[2][i]}), 0.0, 1.0);
        p.lab[i] = hunt(labFromLinear(rgb));
    }
    const Plane ex = convolve(achromatic, w, h, k.d1, k.g),
                ey = convolve(achromatic, w, h, k.g, k.d1);
    const Plane px = convolve(achromatic, w, h, k.d2, k.g),
                py = convolve(achromatic, w, h, k.g, k.d2);
    p.edges.resize(n);
    p.points.resize(n);
    for (size_t i = 0; i < n; ++i) {
        p.edges[i] = std::hypot(ex[i], ey[i]);
        p.points[i] = std::hypot(px[i], py[i]);
    }
    return p;
}

double labF(double t) {
    constexpr double d = 6.0 / 29.0;
    return t > d * d * d ? std::cbrt(t) : t / (3.0 * d * d) + 4.0 / 29.0;
}

} // namespace

glm::dvec3 linearFromSrgb(glm::dvec3 srgb) {
    glm::dvec3 out;
    for (int c = 0; c < 3; ++c)
        out[c] = srgb[c] <= 0.04045 ? srgb[c] / 12.92 : std::pow((srgb[c] + 0.055) / 1.055, 2.4);
    return out;
}

glm::dvec3 ycxczFromLinear(glm::dvec3 rgb) {
    const glm::dvec3 r = xyzFromRgb() * rgb / white();
    return {116.0 * r.y - 16.0, 500.0 * (r.x - r.y), 200.0 * (r.y - r.z)};
}

glm::dvec3 linearFromYcxcz(glm::dvec3 c) {
    const double y = (c.x + 16.0) / 116.0;
    return rgbFromXyz() * (glm::dvec3(c.y / 500.0 + y, y, y - c.z / 200.0) * white());
}

glm::dvec3 labFromLinear(glm::dvec3 rgb) {
    const glm::dvec3 r = xyzFromRgb() * rgb / white();
    const double fx = labF(r.x), fy = labF(r.y), fz = labF(r.z);
    return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

glm::dvec3 hunt(glm::dvec3 lab) {
    return {lab.x, 0.01 * lab.x * lab.y, 0.01 * lab.x * lab.z};
}

double hyab(glm::dvec3 a, glm::dvec3 b) {
    return std::abs(a.x - b.x) + std::hypot(a.y - b.y, a.z - b.z);
}

double maxColorError() {
    static const double e = std::pow(
        hyab(hunt(labFromLinear({0.0, 1.0, 0.0})), hunt(labFromLinear({0.0, 0.0, 1.0}))), kQc);
    return e;
}

double redistributeColorError(double hyabDistance) {
    const double e = std::pow(hyabDistance, kQc), cmax = maxColorError();
    if (e < kPc * cmax) return kPt / (kPc * cmax) * e;
    return kPt + (e - kPc * cmax) / (cmax - kPc * cmax) * (1.0 - kPt);
}

int csfRadius(double ppd) {
    return int(std::ceil(3.0 * std::sqrt(kWidestB / (2.0 * kPi * kPi)) * ppd));
}

double featureError(double edgeTest, double edgeReference, double pointTest,
                    double pointReference) {
    const double d =
        std::max(std::abs(edgeTest - edgeReference), std::abs(pointTest - pointReference));
    return std::pow(d / std::sqrt(2.0), kQf);
}

Result flip(const Image& test, const Image& reference, double ppd) {
    if (test.width != reference.width || test.height != reference.height)
        throw std::invalid_argument("FLIP: the image sizes differ");
    if (test.rgba.size() < test.pixels() * 4 || reference.rgba.size() < reference.pixels() * 4)
        throw std::invalid_argument("FLIP: an image holds fewer than width x height pixels");
    if (!(ppd > 0.0) || !std::isfinite(ppd))
        throw std::invalid_argument("FLIP: pixels per degree must be positive");
    const FeatureKernels k = featureKernels(ppd);
    const Prepared t = prepare(test, ppd, k), r = prepare(reference, ppd, k);
    Result result;
    result.map.resize(test.pixels());
    double sum = 0.0;
    for (size_t i = 0; i < result.map.size(); ++i) {
        const double color = redistributeColorError(hyab(t.lab[i], r.lab[i]));
        const double feature = featureError(t.edges[i], r.edges[i], t.points[i], r.points[i]);
        // Features sharpen the colour error: an exponent below 1 raises it toward 1.
        sum += result.map[i] = std::pow(color, 1.0 - feature);
    }
    result.mean = result.map.empty() ? 0.0 : sum / double(result.map.size());
    return result;
}

std::vector<float> flipErrorMap(const std::vector<double>& map) {
    std::vector<float> rgba(map.size() * 4, 1.0f);
    for (size_t i = 0; i < map.size(); ++i) {
        const glm::vec3 color = std::isfinite(map[i]) ? errorColor(std::clamp(map[i], 0.0, 1.0))
                                                      : glm::vec3(0.0f, 1.0f, 1.0f);
        rgba[4 * i + 0] = color.r;
        rgba[4 * i + 1] = color.g;
        rgba[4 * i + 2] = color.b;
    }
    return rgba;
}

} // namespace ssgi::metrics::flip
