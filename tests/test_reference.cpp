// The path-traced reference against closed-form answers (white furnaces, a disk light over a
// plane, AO of a plane and beside a wall, one bounce between two plates), and the real-time
// direct light measured against it. How a reference render runs (seeds, the noise target, the
// cache, a staged closed model): test_reference_runs.cpp. The `reference` program's own tests
// are in test_metrics.cpp, beside those of `compare`.
#include "reference/cache.h"
#include "reference_support.h"
#include "renderer.h"
#include "scene/primitives.h"
#include "support.h"

#include <cmath>
#include <cstdio>
#include <filesystem>

namespace fs = std::filesystem;
using namespace ssgi;
using namespace ssgi::reference;
using ssgi::test::options;
using ssgi::test::testScene;

namespace {

constexpr double kPi = 3.14159265358979323846;

// Largest |value - expected| over the pixels whose camera sample found geometry (alpha 1).
double worstOnGeometry(const ReferenceImage& image, glm::vec3 expected, size_t& pixels) {
    double worst = 0.0;
    pixels = 0;
    for (size_t i = 0; i < size_t(image.width) * image.height; ++i) {
        if (image.rgba[4 * i + 3] != 1.0f) continue;
        ++pixels;
        for (int c = 0; c < 3; ++c)
            worst = std::max(worst, std::abs(double(image.rgba[4 * i + c]) - expected[c]));
    }
    return worst;
}

// An open plane under a constant sky: every ray leaving it escapes, so full = multi = a * L
// to float rounding, and its AO is 1.
TEST(Reference, WhiteFurnacePlaneAndSkyGradient) {
    const Scene scene = testScene("ref-furnace-plane.json");
    const glm::vec3 expected = glm::vec3(scene.materials[0].baseColorFactor) * scene.sky.zenith;
    for (Mode mode : {Mode::Full, Mode::Multi, Mode::Ao}) {
        const ReferenceImage image = renderReference(scene, scene.camera, options(mode, 32, 8));
        size_t pixels = 0;
        const double worst =
            worstOnGeometry(image, mode == Mode::Ao ? glm::vec3(1.0f) : expected, pixels);
        EXPECT_EQ(pixels, 32u * 32u) << "the plane fills the view";
        std::printf("%s: largest difference from the answer %g\n", modeName(mode), worst);
        EXPECT_LT(worst, 1e-6) << modeName(mode); // measured: 3e-8 (rounding), AO 0
    }
    // A gradient sky: the cosine-weighted mean of w.y over the upper hemisphere is 2/3, so an
    // upward normal gets E = pi (horizon + 2/3 (zenith - horizon)); a downward one sees the
    // ground alone, E = pi ground.
    Scene gradient = scene;
    gradient.sky = {glm::vec3(0.2f, 0.4f, 1.0f), glm::vec3(0.9f, 0.8f, 0.7f), glm::vec3(0.3f)};
    const RayScene rays(gradient);
    const glm::vec3 up =
        estimateIrradiance(gradient, rays, Mode::Full, glm::vec3(0.0f), glm::vec3(0, 1, 0), 100000);
    const glm::vec3 expectedUp =
        float(kPi) * (gradient.sky.horizon + (gradient.sky.zenith - gradient.sky.horizon) / 1.5f);
    std::printf("gradient sky, upward: E = %.5f %.5f %.5f, closed form %.5f %.5f %.5f\n", up.r,
                up.g, up.b, expectedUp.r, expectedUp.g, expectedUp.b);
    for (int c = 0; c < 3; ++c) // tolerance 0.3%; measured: -0.03%, -0.02%, +0.01%
        EXPECT_NEAR(up[c], expectedUp[c], 3e-3 * expectedUp[c]);
    const glm::vec3 down = estimateIrradiance(gradient, rays, Mode::Full, glm::vec3(0, -1, 0),
                                              glm::vec3(0, -1, 0), 1000);
    EXPECT_NEAR(down.g, kPi * 0.3, 1e-5); // measured: exact up to rounding
}

// A convex sphere under a constant sky: a * L in full mode, and multi agrees (nothing bounces
// back). The tessellation's smooth normals send a sliver of directions into the sphere, a loss
// of order (facet angle)^2 / 4.
TEST(Reference, WhiteFurnaceSphereFullAndMultiAgree) {
    const Scene scene = testScene("ref-furnace-sphere.json");
    const double expected = 0.6 * 1.0;
    double means[2];
    for (int k : {0, 1}) {
        const Mode mode = k == 0 ? Mode::Full : Mode::Multi;
        const ReferenceImage image = renderReference(scene, scene.camera, options(mode, 48, 16));
        double sum[2] = {0.0, 0.0}; // sky, sphere
        size_t count[2] = {0, 0};
        for (size_t i = 0; i < size_t(48 * 48); ++i) {
            const float coverage = image.rgba[4 * i + 3];
            if (coverage != 0.0f && coverage != 1.0f) continue; // the silhouette
            sum[size_t(coverage)] += image.rgba[4 * i + 1];
            ++count[size_t(coverage)];
        }
        ASSERT_GT(std::min(count[0], count[1]), 500u);
        EXPECT_EQ(sum[0] / double(count[0]), 1.0) << "camera rays that miss see the sky";
        means[k] = sum[1] / double(count[1]);
        std::printf("%s: mean radiance on the sphere %.8f (expected %.8f)\n", modeName(mode),
                    means[k], expected);
        // Tolerance 1e-4 relative (the smooth normals' sliver); measured: 0.60000002 in both.
        EXPECT_NEAR(means[k], expected, 1e-4 * expected) << modeName(mode);
    }
    EXPECT_NEAR(means[0], means[1], 1e-4);
}

// A white furnace that is closed but for an opening: the inside of a sphere of albedo a with a
// cap cut away, under a constant sky L. Inside a sphere every surface element sees every other
// one with the same form factor dA / (4 pi R^2), so an interior point receives the sky through
// the opening's fraction f of the sphere's area and the wall's radiance B through the rest:
// E = pi (f L + (1 - f) B) and B = a E / pi, hence E = pi f L / (1 - a (1 - f)) with every
// bounce (multi), and pi f L with none (full: the sky on the visible surface only).
TEST(Reference, SphericalCavityUnderTheSkyMatchesTheFormFactorAnswer) {
    const double a = 0.5, sky = 1.0, cut = 0.5;
    Scene scene;
    Material material;
    material.baseColorFactor = glm::vec4(glm::vec3(float(a)), 1.0f);
    scene.materials = {material};
    const Mesh sphere = makeSphere(glm::vec3(0.0f), 1.0f, 256, 0);
    Mesh cavity = sphere;
    cavity.indices.clear();
    double kept = 0.0, removed = 0.0;
    for (size_t t = 0; t + 2 < sphere.indices.size(); t += 3) {
        glm::vec3 v[3];
        for (size_t k = 0; k < 3; ++k)
            v[k] = sphere.vertices[sphere.indices[t + k]].position;
        const double area = 0.5 * glm::length(glm::cross(v[1] - v[0], v[2] - v[0]));
        const bool open = (v[0].y + v[1].y + v[2].y) / 3.0f > float(cut);
        (open ? removed : kept) += area;
        if (!open)
            cavity.indices.insert(cavity.indices.end(), &sphere.indices[t], &sphere.indices[t] + 3);
    }
    scene.meshes = {cavity};
    scene.instances = {{0, glm::mat4(1.0f)}};
    for (const Vertex& v : cavity.vertices)
        scene.bounds.extend(v.position);
    scene.light.intensity = 0.0f;
    scene.sky.zenith = scene.sky.horizon = scene.sky.ground = glm::vec3(float(sky));
    const double f = removed / (kept + removed); // 0.25 for a smooth sphere cut at y = 0.5

    const RayScene rays(scene);
    const glm::vec3 bottom(0.0f, -1.0f, 0.0f), up(0.0f, 1.0f, 0.0f);
    const double full = estimateIrradiance(scene, rays, Mode::Full, bottom, up, 400000, 3).x;
    const double multi = estimateIrradiance(scene, rays, Mode::Multi, bottom, up, 200000, 4).x;
    const double expectedFull = kPi * f * sky, expectedMulti = expectedFull / (1.0 - a * (1.0 - f));
    std::printf("f = %.5f: full %.5f (closed form %.5f, %+.3f%%), multi %.5f (%.5f, %+.3f%%)\n", f,
                full, expectedFull, 100.0 * (full / expectedFull - 1.0), multi, expectedMulti,
                100.0 * (multi / expectedMulti - 1.0));
    // Tolerance 1.5% (about 5 standard errors); measured: full +0.28%, multi +0.11% (and with
    // 4M and 3M samples, +0.06% and -0.03%: no bias beyond the noise).
    EXPECT_NEAR(full, expectedFull, 0.015 * expectedFull);
    EXPECT_NEAR(multi, expectedMulti, 0.015 * expectedMulti);
}

double diskIrradiance(double intensity, double r, double h) {
    return 2.0 * intensity / (r * r) * (1.0 - h / std::sqrt(h * h + r * r));
}

// Irradiance on the floor below the centre of a downward disk light, for several radii, and
// the point light as the limit.
TEST(Reference, DiskLightIrradianceBelowItsCentre) {
    Scene scene = testScene("ref-disk-light.json");
    const double intensity = scene.light.intensity, h = scene.light.position.y;
    for (float r : {0.25f, 0.5f, 1.0f}) {
        scene.light.radius = r;
        const RayScene rays(scene);
        const glm::vec3 e = estimateIrradiance(scene, rays, Mode::Direct, glm::vec3(0.0f),
                                               glm::vec3(0, 1, 0), 200000);
        const double expected = diskIrradiance(intensity, r, h);
        std::printf("r = %.2f: E = %.6f, closed form %.6f (%+.4f%%)\n", r, e.x, expected,
                    100.0 * (e.x / expected - 1.0));
        // Tolerance 0.3% (about 6 standard errors at r = 1); measured: -0.003% (r 0.25),
        // -0.012% (r 0.5), -0.049% (r 1); with 4M samples and two seeds: within 0.016%.
        EXPECT_NEAR(e.x, expected, 3e-3 * expected) << "radius " << r;
    }
    scene.light.radius = 0.0f;
    const RayScene rays(scene);
    const glm::vec3 point =
        estimateIrradiance(scene, rays, Mode::Direct, glm::vec3(0.0f), glm::vec3(0, 1, 0), 16);
    std::printf("r = 0: E = %.7f, I0 / h^2 = %.7f\n", point.x, intensity / (h * h));
    EXPECT_NEAR(point.x, intensity / (h * h), 1e-6); // measured: exact (no random number)
    scene.light.radius = 1e-3f;
    const RayScene small(scene);
    const glm::vec3 tiny =
        estimateIrradiance(scene, small, Mode::Direct, glm::vec3(0.0f), glm::vec3(0, 1, 0), 1000);
    // The closed form's limit: 1 - 3 r^2 / (4 h^2) of I0 / h^2, a 7.5e-7 difference.
    std::printf("r = 0.001: E = %.7f\n", tiny.x);
    EXPECT_NEAR(tiny.x, intensity / (h * h), 1e-5 * intensity);
}

// The floor beside the wall: the fraction of the projected-hemisphere disk the wall hides.
// Farther than the radius from it, the floor is an open plane: visibility 1 exactly.
TEST(Reference, AoOfAnOpenPlaneAndBesideAWall) {
    Scene scene = testScene("ref-ao-wall.json");
    const double radius = 1.0;
    scene.settings.ao_radius = radius;
    const RayScene rays(scene);
    for (glm::vec3 p : {glm::vec3(0, 0, -1.5f), glm::vec3(2, 0, -3), glm::vec3(-4, 0, -1.01f)})
        EXPECT_EQ(estimateIrradiance(scene, rays, Mode::Ao, p, glm::vec3(0, 1, 0), 4096).x, 1.0f)
            << "open floor at z = " << p.z;
    for (double s : {0.05, 0.25, 0.5, 0.75, 0.95}) {
        const glm::vec3 p(0.3f, 0.0f, -float(s * radius));
        const glm::vec3 v =
            estimateIrradiance(scene, rays, Mode::Ao, p, glm::vec3(0, 1, 0), 100000, 11);
        const double expected = 1.0 - (std::acos(s) - s * std::sqrt(1.0 - s * s)) / kPi;
        std::printf("s = %.2f: visibility %.5f, closed form %.5f\n", s, v.x, expected);
        // Binomial standard error <= 0.0016 at 100k samples; tolerance 0.006. Measured
        // differences: +0.0017, +0.0023, +0.0015, +0.0007, +0.0003 (one seed for all five
        // points, hence the common sign; with 2M samples and three seeds: within 0.0005).
        EXPECT_NEAR(v.x, expected, 0.006) << "s = " << s;
    }
}

// One bounce: the ceiling point above the light gathers the floor's reflected spot light.
TEST(Reference, OneBounceBetweenFacingPlatesMatchesQuadrature) {
    const Scene scene = testScene("ref-two-plates.json");
    const SpotLight& light = scene.light;
    const double a = scene.materials[0].baseColorFactor.r, i0 = light.intensity;
    const double h = light.position.y, ceiling = 2.0;
    const double cosOuter = std::cos(double(light.outerConeAngle));
    const double cosInner = std::cos(double(light.innerConeAngle));
    // Simpson's rule out to the edge of the outer cone, where the integrand reaches 0.
    const double edge = h * std::tan(double(light.outerConeAngle));
    const int steps = 20000;
    double integral = 0.0;
    for (int k = 0; k <= steps; ++k) {
        const double rho = edge * k / steps;
        const double t = std::clamp(
            (h / std::sqrt(h * h + rho * rho) - cosOuter) / (cosInner - cosOuter), 0.0, 1.0);
        const double f = a / kPi * i0 * t * t * h / std::pow(h * h + rho * rho, 1.5) * ceiling *
                         ceiling / std::pow(ceiling * ceiling + rho * rho, 2.0) * 2.0 * kPi * rho;
        integral += f * (k == 0 || k == steps ? 1.0 : (k % 2 ? 4.0 : 2.0));
    }
    integral *= edge / steps / 3.0;

    const RayScene rays(scene);
    const glm::vec3 e = estimateIrradiance(scene, rays, Mode::Indirect, glm::vec3(0, ceiling, 0),
                                           glm::vec3(0, -1, 0), 400000, 5);
    std::printf("indirect irradiance %.6f, quadrature %.6f (%+.3f%%)\n", e.x, integral,
                100.0 * (e.x / integral - 1.0));
    // Tolerance 1.5% (about 4 standard errors at 400k samples); measured: +0.196% (and with
    // 4M samples and four seeds: -0.07% to +0.18%, mean +0.05%).
    EXPECT_NEAR(e.x, integral, 0.015 * integral);
    // The direct light cannot reach the ceiling (the cone points down): indirect is all there is.
    const glm::vec3 direct = estimateIrradiance(scene, rays, Mode::Direct, glm::vec3(0, ceiling, 0),
                                                glm::vec3(0, -1, 0), 64);
    EXPECT_EQ(direct.x, 0.0f);
}

class ReferenceAgainstRealTime : public test::VulkanTest {};

// The real-time direct light (a point sample per pixel centre, hard shadow-map test) against
// the reference's direct light for a point light (the same pixel centres, exact visibility)
// on the Cornell box, over the pixels that show geometry.
TEST_F(ReferenceAgainstRealTime, DirectLightOfAPointLight) {
    Scene scene = loadScene(test::sourcePath("scenes/cornell-box.json"));
    scene.light.radius = 0.0f;
    scene.settings.shadow_taps = 1; // the hard shadow-map test, no filtering
    const uint32_t size = 128;
    Renderer renderer(test::context(), scene, {size, size, "final"});
    renderer.renderFrame(scene.camera);
    const std::vector<float> direct = renderer.readImage("direct");
    const std::vector<float> position = renderer.readImage("gbuffer.position");
    // A point light seen from pixel centres involves no random number: 2 samples are exact.
    const ReferenceImage reference = cachedReference(scene, options(Mode::Direct, size, 2));

    // A shadow edge pixel: lit in the reference while a pixel within two is not, or the other
    // way. There one pixel's point sample falls on either side of the edge depending on the
    // shadow map's texels, and a flip is a 100% error; elsewhere the shading must agree. Two
    // pixels, not one: the floor's last row in front of the short block is one pixel tall, and
    // the short block's shadow edge crosses it at a slant (the 2048-texel map puts it two
    // pixels from the reference's, the 1024-texel one pixel).
    auto lit = [&](long x, long y) {
        const size_t i = size_t(y) * size + size_t(x);
        return reference.rgba[4 * i] + reference.rgba[4 * i + 1] + reference.rgba[4 * i + 2] > 0;
    };
    double relSum = 0.0, relSumAwayFromEdges = 0.0;
    size_t pixels = 0, awayFromEdges = 0, coverageDisagrees = 0, farOff = 0;
    for (long y = 0; y < long(size); ++y)
        for (long x = 0; x < long(size); ++x) {
            const size_t i = size_t(y) * size + size_t(x);
            const bool geometry = position[4 * i + 3] != 0.0f;
            coverageDisagrees += geometry != (reference.rgba[4 * i + 3] == 1.0f);
            if (!geometry) continue;
            ++pixels;
            double pixelRel = 0.0;
            for (size_t c = 0; c < 3; ++c) {
                const double a = direct[4 * i + c], b = reference.rgba[4 * i + c];
                pixelRel += (a - b) * (a - b) / (b * b + 0.01) / 3.0;
            }
            relSum += pixelRel;
            farOff += pixelRel > 0.01; // more than 10% off
            bool edge = false;
            for (long dy = -2; dy <= 2; ++dy)
                for (long dx = -2; dx <= 2; ++dx) {
                    const long nx = x + dx, ny = y + dy;
                    if (nx >= 0 && ny >= 0 && nx < long(size) && ny < long(size))
                        edge |= lit(nx, ny) != lit(x, y);
                }
            if (edge) continue;
            ++awayFromEdges;
            relSumAwayFromEdges += pixelRel;
        }
    const double relMse = relSum / double(pixels);
    const double relMseAway = relSumAwayFromEdges / double(awayFromEdges);
    std::printf("geometry pixels %zu: relMSE %.6f, %zu pixels more than 10%% off; away from "
                "shadow edges (%zu pixels): relMSE %.3g; coverage differs at %zu\n",
                pixels, relMse, farOff, awayFromEdges, relMseAway, coverageDisagrees);
    EXPECT_GT(pixels, size_t(size) * size * 9 / 10);
    EXPECT_EQ(coverageDisagrees, 0u); // measured: 0, the same pixel centres
    // Measured at 128x128: relMSE 0.0340 (27 pixels more than 10% off, all on the shadow-map-
    // aliased shadow edges; 0.0389 and 31 with the 1024-texel map); tolerance 0.06 and 60.
    EXPECT_LT(relMse, 0.06);
    EXPECT_LT(farOff, 60u);
    // Measured: 5.5e-6 (3.6e-5 with the 1024-texel map and one pixel's edge, nearly all of it
    // one pixel where the wall meets the floor and the map shadowed the floor); tolerance 1e-4.
    EXPECT_LT(relMseAway, 1e-4);
}

} // namespace
