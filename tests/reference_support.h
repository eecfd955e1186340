// What the reference's tests share: their scenes and the options of a render.
#pragma once

#include "reference/render.h"
#include "scene/scene.h"
#include "support.h"

#include <string>

namespace ssgi::test {

// A scene of tests/scenes/.
inline Scene testScene(const std::string& name) {
    return loadScene(sourcePath("tests/scenes/" + name));
}

// A square render of `size` pixels a side, `spp` samples per pixel.
inline reference::ReferenceOptions options(reference::Mode mode, uint32_t size, uint32_t spp) {
    reference::ReferenceOptions o;
    o.mode = mode;
    o.width = o.height = size;
    o.spp = spp;
    return o;
}

} // namespace ssgi::test
