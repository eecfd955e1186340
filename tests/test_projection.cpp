// Projection and reprojection math (thesis 3.1.1, equations 1-3) against independent geometry.
#include "frame_uniforms.h"
#include "scene/camera.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

using namespace ssgi;

namespace {

Camera lookingAt(glm::vec3 position, glm::vec3 target, float yfovDeg) {
    Camera c;
    c.position = position;
    c.orientation = lookRotation(target - position, glm::vec3(0, 1, 0));
    c.yfov = glm::radians(yfovDeg);
    c.znear = 0.1f;
    c.zfar = 100.0f;
    return c;
}

TEST(Projection, TargetProjectsToTheImageCentre) {
    Camera c = lookingAt({1, 2, 3}, {4, 0, -5}, 50.0f);
    glm::mat4 vp = projectionMatrix(c, 1.5f) * viewMatrix(c);
    glm::vec3 uvd;
    ASSERT_TRUE(projectToTexture(vp, {4, 0, -5}, uvd));
    EXPECT_NEAR(uvd.x, 0.5f, 1e-5f);
    EXPECT_NEAR(uvd.y, 0.5f, 1e-5f);
    EXPECT_GT(uvd.z, 0.0f);
    EXPECT_LT(uvd.z, 1.0f);
}

TEST(Projection, UpIsTheTopOfTheImageAndRightIsRight) {
    Camera c = lookingAt({0, 0, 5}, {0, 0, 0}, 60.0f);
    glm::mat4 vp = projectionMatrix(c, 1.0f) * viewMatrix(c);
    glm::vec3 above, right;
    ASSERT_TRUE(projectToTexture(vp, {0, 1, 0}, above));
    ASSERT_TRUE(projectToTexture(vp, {1, 0, 0}, right));
    EXPECT_LT(above.y, 0.5f); // v = 0 is the top row
    EXPECT_GT(right.x, 0.5f);
}

TEST(Projection, EdgeOfTheFieldOfViewMapsToTheImageEdge) {
    Camera c = lookingAt({0, 0, 0}, {0, 0, -1}, 90.0f);
    glm::mat4 vp = projectionMatrix(c, 1.0f) * viewMatrix(c);
    glm::vec3 uvd;
    // At 45 degrees up (half of a 90 degree vertical fov) the point lies on the top edge.
    ASSERT_TRUE(projectToTexture(vp, {0, 2, -2}, uvd));
    EXPECT_NEAR(uvd.y, 0.0f, 1e-5f);
}

TEST(Projection, PointsBehindTheCameraDoNotProject) {
    Camera c = lookingAt({0, 0, 0}, {0, 0, -1}, 60.0f);
    glm::mat4 vp = projectionMatrix(c, 1.0f) * viewMatrix(c);
    glm::vec3 uvd;
    EXPECT_FALSE(projectToTexture(vp, {0, 0, 1}, uvd));
}

TEST(Projection, LinearDepthInvertsTheProjectedDepth) {
    Camera c = lookingAt({0, 0, 0}, {0, 0, -1}, 60.0f);
    glm::mat4 vp = projectionMatrix(c, 1.0f) * viewMatrix(c);
    for (float d : {0.1f, 0.5f, 3.0f, 42.0f, 99.0f}) {
        glm::vec3 uvd;
        ASSERT_TRUE(projectToTexture(vp, {0.3f, -0.2f, -d}, uvd));
        EXPECT_NEAR(linearDepth(uvd.z, c.znear, c.zfar), d, d * 1e-4f);
    }
}

// Reverse reprojection of a static point: where it was last frame, from this frame's world
// position, must be exactly where last frame's camera saw it.
TEST(Reprojection, StaticPointReprojectsToWhereThePreviousCameraSawIt) {
    Camera previous = lookingAt({0, 1, 5}, {0, 0, 0}, 45.0f);
    Camera current = lookingAt({0.3f, 1.1f, 4.8f}, {0.05f, 0, 0}, 45.0f);
    glm::mat4 previousVp = projectionMatrix(previous, 1.0f) * viewMatrix(previous);
    const glm::vec3 world(0.2f, -0.1f, 0.4f);
    // The previous frame's pixel for this point, found independently by casting a ray through
    // every candidate pixel centre of a 64x64 grid.
    glm::mat4 inverse = glm::inverse(previousVp);
    float bestError = 1e9f;
    glm::vec2 bestUv;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            glm::vec2 uv((x + 0.5f) / 64.0f, (y + 0.5f) / 64.0f);
            glm::vec4 far = inverse * glm::vec4(uv * 2.0f - 1.0f, 1.0f, 1.0f);
            glm::vec3 dir = glm::normalize(glm::vec3(far) / far.w - previous.position);
            glm::vec3 toPoint = world - previous.position;
            float error = glm::length(toPoint - dir * glm::dot(toPoint, dir));
            if (error < bestError) bestError = error, bestUv = uv;
        }
    // This frame: the G-buffer holds the world position reconstructed from the current pixel and
    // depth; reprojecting it with last frame's matrices (equation 1) must find that pixel.
    glm::mat4 currentVp = projectionMatrix(current, 1.0f) * viewMatrix(current);
    glm::vec3 now;
    ASSERT_TRUE(projectToTexture(currentVp, world, now));
    glm::vec4 h = glm::inverse(currentVp) * glm::vec4(glm::vec2(now) * 2.0f - 1.0f, now.z, 1.0f);
    glm::vec3 worldNow = glm::vec3(h) / h.w;
    EXPECT_LT(glm::length(worldNow - world), 1e-4f);
    glm::vec3 reprojected;
    ASSERT_TRUE(projectToTexture(previousVp, worldNow, reprojected));
    EXPECT_NEAR(reprojected.x, bestUv.x, 1.0f / 64.0f);
    EXPECT_NEAR(reprojected.y, bestUv.y, 1.0f / 64.0f);
}

TEST(LightFrustum, CoversTheConeAndTheSceneDepth) {
    SpotLight light;
    light.position = {0, 2, 0};
    light.direction = {0, -1, 0};
    light.outerConeAngle = glm::radians(40.0f);
    Aabb bounds;
    bounds.extend({-1, 0, -1});
    bounds.extend({1, 2, 1});
    LightFrustum f = lightFrustum(light, bounds);
    EXPECT_GE(f.zfar, 2.0f);
    EXPECT_LT(f.znear, 0.1f);
    glm::vec3 uvd;
    // A point on the cone's edge at the floor lands on the shadow map's border.
    float r = 2.0f * std::tan(glm::radians(40.0f));
    ASSERT_TRUE(projectToTexture(f.viewProjection, {r, 0, 0}, uvd));
    EXPECT_NEAR(std::max(std::abs(uvd.x - 0.5f), std::abs(uvd.y - 0.5f)), 0.5f, 1e-4f);
    ASSERT_TRUE(projectToTexture(f.viewProjection, {0, 0, 0}, uvd));
    EXPECT_NEAR(uvd.x, 0.5f, 1e-5f);
    EXPECT_NEAR(linearDepth(uvd.z, f.znear, f.zfar), 2.0f, 1e-3f);
}

TEST(CameraPath, InterpolatesBetweenKeysAndClampsAtTheEnds) {
    CameraPath path;
    Camera a = lookingAt({0, 0, 0}, {0, 0, -1}, 40.0f);
    Camera b = lookingAt({2, 0, 0}, {2, 0, -1}, 60.0f);
    path.keys = {{0.0f, a}, {2.0f, b}};
    Camera mid = cameraAt(path, 1.0f);
    EXPECT_NEAR(mid.position.x, 1.0f, 1e-6f);
    EXPECT_NEAR(glm::degrees(mid.yfov), 50.0f, 1e-4f);
    EXPECT_EQ(cameraAt(path, -1.0f).position, a.position);
    EXPECT_EQ(cameraAt(path, 5.0f).position, b.position);
}

// The G-buffer keeps a view depth; pixelToWorld takes a pixel centre and that depth back to the
// world point that projects there (gbuffer_position.glsl does the same on the GPU).
TEST(FrameUniforms, PixelToWorldUndoesTheProjection) {
    Camera c = lookingAt({1, 2, 3}, {4, 0, -5}, 50.0f);
    const VkExtent2D size{160, 90};
    const glm::mat4 view = viewMatrix(c), projection = projectionMatrix(c, 160.0f / 90.0f);
    const glm::mat4 toWorld = pixelToWorld(view, projection, size);
    for (const glm::vec3 world : {glm::vec3(4, 0, -5), glm::vec3(2, 1, -1), glm::vec3(-1, 3, -9)}) {
        glm::vec3 uvd;
        ASSERT_TRUE(projectToTexture(projection * view, world, uvd));
        const glm::vec2 pixel = glm::vec2(uvd) * glm::vec2(size.width, size.height);
        const float depth = -(view * glm::vec4(world, 1.0f)).z;
        const glm::vec4 back = toWorld * glm::vec4(pixel * depth, depth, 1.0f);
        EXPECT_NEAR(glm::distance(glm::vec3(back), world), 0.0f, 1e-4f) << world.x;
    }
}

// A scene near the origin keeps it; one far away moves it to the centre of its bounds, which a
// float holds exactly, and what moves to the GPU is the difference, taken in double precision.
TEST(FrameUniforms, TheGpuOriginFollowsAFarScene) {
    EXPECT_EQ(gpuOrigin(Aabb{{-1, 0, -1}, {1, 2, 1}}), glm::dvec3(0.0));
    const Aabb far{{1e5f, 0, 1e5f}, {1e5f + 2, 2, 1e5f + 2}};
    const glm::dvec3 origin = gpuOrigin(far);
    EXPECT_EQ(origin, glm::dvec3(glm::vec3(1e5f + 1, 1, 1e5f + 1)));
    EXPECT_EQ(moved(glm::vec3(1e5f + 2, 2, 1e5f), origin), glm::vec3(1, 1, -1));
    const glm::mat4 at = glm::translate(glm::mat4(1.0f), glm::vec3(1e5f + 2, 2, 1e5f));
    EXPECT_EQ(glm::vec3(moved(at, origin)[3]), glm::vec3(1, 1, -1));
}

} // namespace
