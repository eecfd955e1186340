// A glTF loaded without a scene file (a bare model): framed, lit and grounded whatever its
// scale, a ground plane only where it has no floor of its own, its own camera followed; a scene
// file gets none of this staging.
#include "scene_files.h"

namespace {

// A bare model (no scene file) is staged: the tests below use a box standing clear of the
// origin, alone or on a floor of its own, at scales from millimetres to kilometres.

// A box over [-1, 1] x [0.5, 2] x [-0.5, 0.5] (12 triangles); with `floor`, also a 6 x 6 quad
// facing up at its base, which is then the lowest level of the model.
json boxGltf(bool floor, const json& node) {
    std::vector<float> positions;
    for (int corner = 0; corner < 8; ++corner)
        positions.insert(positions.end(), {corner & 1 ? 1.0f : -1.0f, corner & 2 ? 2.0f : 0.5f,
                                           corner & 4 ? 0.5f : -0.5f});
    // Wound counter-clockwise seen from outside: the base faces down.
    std::vector<uint16_t> indices = {0, 1, 5, 0, 5, 4, 2, 6, 7, 2, 7, 3, 0, 2, 3, 0, 3, 1,
                                     4, 5, 7, 4, 7, 6, 0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5};
    if (floor) {
        positions.insert(positions.end(), {-3, 0.5f, -3, 3, 0.5f, -3, 3, 0.5f, 3, -3, 0.5f, 3});
        indices.insert(indices.end(), {8, 10, 9, 8, 11, 10});
    }
    return triangleGltf(positions, indices, json::array({node}), {0});
}

bool isGround(const ssgi::Instance& instance) {
    return instance.name == "ground";
}

// The bounds of the model's own instances (without the ground plane).
ssgi::Aabb modelBounds(const Scene& scene) {
    ssgi::Aabb bounds;
    for (const ssgi::Instance& instance : scene.instances)
        if (!isGround(instance))
            for (const ssgi::Vertex& v : scene.meshes[size_t(instance.mesh)].vertices)
                bounds.extend(glm::vec3(instance.transform * glm::vec4(v.position, 1.0f)));
    return bounds;
}

bool inside(glm::vec3 p, const ssgi::Aabb& bounds) {
    return glm::all(glm::greaterThanEqual(p, bounds.min)) &&
           glm::all(glm::lessThanEqual(p, bounds.max));
}

glm::vec3 corner(const ssgi::Aabb& bounds, int index) {
    return {index & 1 ? bounds.max.x : bounds.min.x, index & 2 ? bounds.max.y : bounds.min.y,
            index & 4 ? bounds.max.z : bounds.min.z};
}

TEST_F(SceneFiles, BareModelIsFramedAndLitAtEveryScale) {
    float firstIrradiance = 0.0f;
    glm::vec3 firstDirection(0.0f);
    for (float scale : {1.0f, 1e-9f, 1e-3f, 1e3f}) { // scale 1 first: the others match it
        SCOPED_TRACE(scale);
        const json node = {{"mesh", 0},
                           {"scale", {scale, scale, scale}},
                           {"translation", {3 * scale, -scale, 2 * scale}}};
        const Scene scene = loadScene(write("box.gltf", boxGltf(false, node).dump()));
        const ssgi::Aabb model = modelBounds(scene);
        const glm::vec3 center = model.center();
        const float radius = 0.5f * glm::length(model.size());

        // The light is outside the model, aimed at its centre, with the whole model inside its
        // full-intensity cone, above the camera and on its side of the model.
        const ssgi::SpotLight& light = scene.light;
        EXPECT_FALSE(inside(light.position, model));
        EXPECT_GT(glm::distance(light.position, center), radius);
        EXPECT_GT(glm::dot(light.direction, glm::normalize(center - light.position)), 0.99999f);
        for (int c = 0; c < 8; ++c) {
            const glm::vec3 toCorner = glm::normalize(corner(model, c) - light.position);
            EXPECT_LE(std::acos(std::min(glm::dot(toCorner, light.direction), 1.0f)),
                      light.innerConeAngle + 1e-3f);
        }
        EXPECT_LT(light.outerConeAngle, glm::radians(89.0f));
        EXPECT_GT(light.position.y, scene.camera.position.y);
        const glm::vec3 lightSide = light.position - center,
                        cameraSide = scene.camera.position - center;
        EXPECT_GT(lightSide.x * cameraSide.x + lightSide.z * cameraSide.z, 0.0f);
        // The same irradiance at the centre whatever the units: intensity follows distance^2.
        const float irradiance =
            light.intensity / glm::dot(center - light.position, center - light.position);
        EXPECT_NEAR(irradiance, ssgi::kBareModelIrradiance, 1e-3f);
        if (firstIrradiance == 0.0f) firstIrradiance = irradiance;
        EXPECT_NEAR(irradiance, firstIrradiance, 1e-4f * firstIrradiance);
        // The same direction too: the light's side is the camera's at every scale (at 1e-9 an
        // absolute floor of 1e-6 units on the camera's offset sent it to +Z).
        if (firstDirection == glm::vec3(0.0f)) firstDirection = light.direction;
        EXPECT_LT(glm::distance(light.direction, firstDirection), 1e-4f);

        // The camera is outside the model, looks down at it, has its centre in the middle of
        // the frame and every corner of its bounds within the frame.
        const ssgi::Camera& camera = scene.camera;
        EXPECT_FALSE(inside(camera.position, model));
        EXPECT_LT((camera.orientation * glm::vec3(0, 0, -1)).y, -0.3f);
        const glm::mat4 viewProjection =
            ssgi::projectionMatrix(camera, 1.0f) * ssgi::viewMatrix(camera);
        glm::vec3 projected;
        ASSERT_TRUE(ssgi::projectToTexture(viewProjection, center, projected));
        EXPECT_NEAR(projected.x, 0.5f, 1e-3f);
        EXPECT_NEAR(projected.y, 0.5f, 1e-3f);
        float widest = 0.0f;
        for (int c = 0; c < 8; ++c) {
            ASSERT_TRUE(ssgi::projectToTexture(viewProjection, corner(model, c), projected));
            EXPECT_GT(projected.z, 0.0f);
            EXPECT_LT(projected.z, 1.0f);
            const float fromMiddle =
                std::max(std::abs(projected.x - 0.5f), std::abs(projected.y - 0.5f));
            EXPECT_LE(fromMiddle, 0.5f);
            widest = std::max(widest, fromMiddle);
        }
        EXPECT_GT(widest, 0.4f) << "the model fills most of the frame";

        // A daylight sky, and a ground plane under the model and around it, facing up.
        EXPECT_GT(scene.sky.horizon.b, 0.1f);
        EXPECT_GT(scene.sky.zenith.b, scene.sky.zenith.r);
        const auto ground = std::find_if(scene.instances.begin(), scene.instances.end(), isGround);
        ASSERT_NE(ground, scene.instances.end());
        ssgi::Aabb plane;
        for (const ssgi::Vertex& v : scene.meshes[size_t(ground->mesh)].vertices) {
            plane.extend(v.position);
            EXPECT_GT(v.normal.y, 0.999f);
        }
        EXPECT_LE(plane.max.y, model.min.y);
        EXPECT_GT(plane.max.y, model.min.y - 0.01f * radius);
        EXPECT_LT(plane.min.x, model.min.x - 2 * radius);
        EXPECT_GT(plane.max.z, model.max.z + 2 * radius);
        EXPECT_TRUE(inside(plane.min, scene.bounds) && inside(plane.max, scene.bounds));
        // The AO radius stays the model's, not the ground's: 1.25% of its diagonal beside the
        // sky's visibility (on by default), 5% without it.
        EXPECT_NEAR(ssgi::aoRadius(scene), 0.0125f * glm::length(model.size()),
                    1e-4f * glm::length(model.size()));
        Scene withoutSkyMaps = scene;
        withoutSkyMaps.settings.sky_visibility = false;
        EXPECT_NEAR(ssgi::aoRadius(withoutSkyMaps), 0.05f * glm::length(model.size()),
                    1e-4f * glm::length(model.size()));
    }
}

TEST_F(SceneFiles, GroundPlaneOnlyWhereTheModelHasNoFloor) {
    auto grounds = [](const Scene& scene) {
        return std::count_if(scene.instances.begin(), scene.instances.end(), isGround);
    };
    const std::string box = write("box.gltf", boxGltf(false, {{"mesh", 0}}).dump());
    const std::string onFloor = write("floor.gltf", boxGltf(true, {{"mesh", 0}}).dump());
    EXPECT_EQ(grounds(loadScene(box)), 1);
    EXPECT_EQ(grounds(loadScene(onFloor)), 0) << "its own floor spans its footprint";
    // The setting turns it off (given as `render --set` gives it, while loading).
    const Scene off = loadScene(box, {{"ground_plane", 0}});
    EXPECT_EQ(grounds(off), 0);
    EXPECT_NEAR(off.bounds.min.y, 0.5f, 1e-6f);
    EXPECT_THROW(ssgi::checkSetting("--set", "ground_plane", 2), InputError);

    // A base facing up counts as a floor when it covers half the footprint, not less.
    Scene scene;
    scene.meshes.push_back({{{{-1, 0, -1}, {0, 1, 0}, {}},
                             {{1, 0, -1}, {0, 1, 0}, {}},
                             {{1, 0, 1}, {0, 1, 0}, {}},
                             {{-1, 0, 1}, {0, 1, 0}, {}},
                             {{4, 4, 4}, {0, 1, 0}, {}}},
                            {0, 2, 1, 0, 3, 2, 0, 1, 4},
                            0});
    scene.instances.push_back({0, glm::mat4(1.0f), ""});
    ssgi::Aabb bounds;
    for (const ssgi::Vertex& v : scene.meshes[0].vertices)
        bounds.extend(v.position);
    EXPECT_FALSE(ssgi::hasGround(scene, bounds)); // base 4 of a 5 x 5 footprint
    scene.meshes[0].vertices[4].position = {1.5f, 4, 1.5f};
    bounds = {};
    for (const ssgi::Vertex& v : scene.meshes[0].vertices)
        bounds.extend(v.position);
    EXPECT_TRUE(ssgi::hasGround(scene, bounds)); // base 4 of a 2.5 x 2.5 footprint
}

TEST_F(SceneFiles, SceneFilesGetNoBareModelStaging) {
    // A scene file without light, camera or sky keeps the light straight down from inside the
    // top of its bounds, the camera on +Z, a black sky and no ground, as before.
    write("box.gltf", boxGltf(false, {{"mesh", 0}}).dump());
    const Scene scene = loadScene(write("box.json", json{{"gltf", "box.gltf"}}.dump()));
    EXPECT_EQ(std::count_if(scene.instances.begin(), scene.instances.end(), isGround), 0);
    EXPECT_NEAR(glm::distance(scene.light.direction, glm::vec3(0, -1, 0)), 0, 1e-6);
    EXPECT_LT(scene.light.position.y, scene.bounds.max.y);
    EXPECT_NEAR(scene.camera.position.x, 0.0f, 1e-6f);
    EXPECT_EQ(scene.sky.zenith, glm::vec3(0.0f));
    EXPECT_EQ(scene.settings.ao_radius, 0.0);
    // A scene file gets a ground plane by asking for one.
    const Scene asked = loadScene(write(
        "ground.json", json{{"gltf", "box.gltf"}, {"settings", {{"ground_plane", 1}}}}.dump()));
    EXPECT_EQ(std::count_if(asked.instances.begin(), asked.instances.end(), isGround), 1);
    EXPECT_EQ(asked.sky.zenith, glm::vec3(0.0f));
}

TEST_F(SceneFiles, BareModelLightFollowsItsGltfCamera) {
    // The file's camera looks at the box from -X; the default light comes from that side.
    json gltf = boxGltf(false, {{"mesh", 0}});
    gltf["nodes"].push_back({{"camera", 0},
                             {"translation", {-8, 1.25, 0}},
                             {"rotation", {0, -0.70710678, 0, 0.70710678}}});
    gltf["scenes"][0]["nodes"].push_back(1);
    gltf["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.7}, {"znear", 0.1}}}}};
    const Scene scene = loadScene(write("camera.gltf", gltf.dump()));
    EXPECT_NEAR(glm::distance(scene.camera.position, glm::vec3(-8, 1.25, 0)), 0, 1e-5);
    EXPECT_NEAR(glm::distance(scene.camera.orientation * glm::vec3(0, 0, -1), glm::vec3(1, 0, 0)),
                0, 1e-5);
    EXPECT_LT(scene.light.position.x, -1.0f);
    EXPECT_GT(glm::dot(scene.light.direction,
                       glm::normalize(modelBounds(scene).center() - scene.light.position)),
              0.99999f);
}

} // namespace
