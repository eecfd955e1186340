#include "stability/measures.h"

namespace ssgi::stability {

size_t countNonFinite(const Pixels& rgba) {
    return size_t(
        std::count_if(rgba.begin(), rgba.end(), [](float v) { return !std::isfinite(v); }));
}

double luminance(const Pixels& rgba, size_t i) {
    return 0.2126 * rgba[4 * i] + 0.7152 * rgba[4 * i + 1] + 0.0722 * rgba[4 * i + 2];
}

Mask geometryMask(const View& v) {
    Mask m(v.pixels());
    for (size_t i = 0; i < m.size(); ++i)
        m[i] = v.geometry(i);
    return m;
}

Mask subtract(Mask a, const Mask& b) {
    for (size_t i = 0; i < a.size(); ++i)
        a[i] = a[i] && !b[i];
    return a;
}

double maskedRelMse(const Pixels& test, const Pixels& reference, const Mask& mask) {
    double sum = 0.0;
    size_t n = 0;
    for (size_t i = 0; i < mask.size(); ++i) {
        if (!mask[i]) continue;
        ++n;
        for (size_t c = 0; c < 3; ++c) {
            const double a = test[4 * i + c], b = reference[4 * i + c];
            sum += (a - b) * (a - b) / (b * b + metrics::kRelMseEpsilon);
        }
    }
    return n ? sum / (3.0 * double(n)) : kNaN;
}

glm::mat4 viewProjection(const View& v) {
    return projectionMatrix(v.camera, float(v.width) / float(v.height)) * viewMatrix(v.camera);
}

Lookup lookup(const View& before, const glm::mat4& viewProjection, glm::vec3 p) {
    glm::vec3 uvd;
    Lookup l;
    if (!projectToTexture(viewProjection, p, uvd)) return l;
    l.x = long(std::floor(uvd.x * float(before.width)));
    l.y = long(std::floor(uvd.y * float(before.height)));
    l.onScreen = l.x >= 0 && l.y >= 0 && l.x < long(before.width) && l.y < long(before.height);
    return l;
}

long correspondingPixel(const View& before, const glm::mat4& viewProjection, const View& now,
                        size_t i) {
    const glm::vec3 p = now.world(i);
    const Lookup l = lookup(before, viewProjection, p);
    if (!l.onScreen) return -1;
    const float tolerance = 0.03f * glm::distance(p, before.camera.position);
    long best = -1;
    float bestGap = tolerance;
    for (long y = std::max(l.y - 1, 0L); y <= std::min(l.y + 1, long(before.height) - 1); ++y)
        for (long x = std::max(l.x - 1, 0L); x <= std::min(l.x + 1, long(before.width) - 1); ++x) {
            const size_t j = size_t(y) * before.width + size_t(x);
            if (!before.geometry(j)) continue;
            const float gap = glm::distance(before.world(j), p);
            if (gap < bestGap) best = long(j), bestGap = gap;
        }
    return best;
}

bool hiddenBefore(const View& before, const glm::mat4& viewProjection, const View& now, size_t i) {
    const glm::vec3 p = now.world(i);
    const Lookup l = lookup(before, viewProjection, p);
    if (!l.onScreen) return false;
    const float reach = glm::distance(p, before.camera.position);
    for (long y = std::max(l.y - 1, 0L); y <= std::min(l.y + 1, long(before.height) - 1); ++y)
        for (long x = std::max(l.x - 1, 0L); x <= std::min(l.x + 1, long(before.width) - 1); ++x) {
            const size_t j = size_t(y) * before.width + size_t(x);
            if (!before.geometry(j) || before.distance(j) > 0.98f * reach) return false;
        }
    return true;
}

Mask disoccludedMask(const View& before, const View& now) {
    Mask m(now.pixels());
    const glm::mat4 vp = viewProjection(before);
    for (size_t i = 0; i < m.size(); ++i)
        m[i] = now.geometry(i) && hiddenBefore(before, vp, now, i);
    return m;
}

Mask unseenMask(const View& before, const View& now) {
    Mask m(now.pixels());
    const glm::mat4 vp = viewProjection(before);
    for (size_t i = 0; i < m.size(); ++i)
        m[i] = now.geometry(i) &&
               (!lookup(before, vp, now.world(i)).onScreen || hiddenBefore(before, vp, now, i));
    return m;
}

double flicker(const View& before, const View& now, const Mask& mask) {
    const bool still = before.camera.position == now.camera.position &&
                       before.camera.orientation == now.camera.orientation &&
                       before.width == now.width && before.height == now.height;
    const glm::mat4 vp = viewProjection(before);
    double change = 0.0, level = 0.0;
    for (size_t i = 0; i < now.pixels(); ++i) {
        if ((!mask.empty() && !mask[i]) || !now.geometry(i)) continue;
        const long j = still ? long(i) : correspondingPixel(before, vp, now, i);
        if (j < 0) continue;
        change += std::abs(now.lighting(i) - before.lighting(size_t(j)));
        level += now.lighting(i);
    }
    return level > 0.0 ? change / level : kNaN;
}

double staleFraction(const Pixels& image, const Pixels& oldImage, const Pixels& newImage,
                     const Mask& mask) {
    double along = 0.0, norm = 0.0;
    for (size_t i = 0; i < mask.size(); ++i) {
        if (!mask[i]) continue;
        const double change = luminance(oldImage, i) - luminance(newImage, i);
        along += (luminance(image, i) - luminance(newImage, i)) * change;
        norm += change * change;
    }
    return norm > 0.0 ? along / norm : kNaN;
}

Mask changedMask(const Pixels& a, const Pixels& b, const Mask& within, double relative) {
    Mask m(within.size());
    for (size_t i = 0; i < m.size(); ++i) {
        const double la = luminance(a, i), lb = luminance(b, i);
        m[i] = within[i] && std::abs(la - lb) > relative * 0.5 * (la + lb) + 1e-3;
    }
    return m;
}

Mask grazingMask(const View& v, float cosine) {
    Mask m(v.pixels());
    for (size_t i = 0; i < m.size(); ++i) {
        if (!v.geometry(i)) continue;
        const glm::vec3 n(v.normal[4 * i], v.normal[4 * i + 1], v.normal[4 * i + 2]);
        m[i] = std::abs(glm::dot(n, glm::normalize(v.camera.position - v.world(i)))) < cosine;
    }
    return m;
}

std::vector<float> distances(const View& v) {
    std::vector<float> d(v.pixels());
    for (size_t i = 0; i < d.size(); ++i)
        d[i] = v.geometry(i) ? v.distance(i) : std::numeric_limits<float>::infinity();
    return d;
}

Mask dilate(const Mask& m, uint32_t width, uint32_t height, int radius) {
    Mask out(m.size());
    for (long y = 0; y < long(height); ++y)
        for (long x = 0; x < long(width); ++x)
            for (long dy = -radius; dy <= radius && !out[size_t(y) * width + x]; ++dy)
                for (long dx = -radius; dx <= radius; ++dx) {
                    const long xx = x + dx, yy = y + dy;
                    if (xx >= 0 && yy >= 0 && xx < long(width) && yy < long(height) &&
                        m[size_t(yy) * width + size_t(xx)]) {
                        out[size_t(y) * width + x] = 1;
                        break;
                    }
                }
    return out;
}

Mask thinMask(const View& v, int maxWidth, float ratio, int border) {
    const std::vector<float> d = distances(v);
    const long w = v.width, h = v.height;
    Mask thin(v.pixels());
    auto farther = [&](long x, long y, float than) {
        return x >= 0 && y >= 0 && x < w && y < h && d[size_t(y * w + x)] > ratio * than;
    };
    for (long y = 0; y < h; ++y)
        for (long x = 0; x < w; ++x) {
            const float here = d[size_t(y * w + x)];
            if (!std::isfinite(here)) continue;
            for (int axis = 0; axis < 2 && !thin[size_t(y * w + x)]; ++axis) {
                const long sx = axis == 0, sy = axis == 1;
                bool before = false, after = false;
                for (int k = 1; k <= maxWidth && !before; ++k)
                    before = farther(x - k * sx, y - k * sy, here);
                for (int k = 1; k <= maxWidth && !after; ++k)
                    after = farther(x + k * sx, y + k * sy, here);
                thin[size_t(y * w + x)] = before && after;
            }
        }
    return dilate(thin, v.width, v.height, border);
}

Mask depthEdgeMask(const View& v, float ratio, int band) {
    const std::vector<float> d = distances(v);
    Mask edges(v.pixels());
    auto compare = [&](size_t i, size_t j) {
        const float lo = std::min(d[i], d[j]), hi = std::max(d[i], d[j]);
        if (std::isfinite(lo) && hi > ratio * lo) edges[i] = edges[j] = 1;
    };
    for (size_t y = 0; y < v.height; ++y)
        for (size_t x = 0; x < v.width; ++x) {
            if (x + 1 < v.width) compare(y * v.width + x, y * v.width + x + 1);
            if (y + 1 < v.height) compare(y * v.width + x, (y + 1) * v.width + x);
        }
    Mask m = dilate(edges, v.width, v.height, band);
    for (size_t i = 0; i < m.size(); ++i)
        m[i] = m[i] && v.geometry(i);
    return m;
}

Mask nearBoxMask(const View& v, const Aabb& box, float reach) {
    Mask m(v.pixels());
    for (size_t i = 0; i < m.size(); ++i) {
        if (!v.geometry(i)) continue;
        const glm::vec3 p = v.world(i);
        const float gap =
            glm::length(glm::max(glm::max(box.min - p, p - box.max), glm::vec3(0.0f)));
        m[i] = gap > 0.02f * reach && gap < reach;
    }
    return m;
}

int framesUntilWithin(const std::vector<double>& errors, double tolerance) {
    int since = -1;
    for (size_t k = 0; k < errors.size(); ++k) {
        const bool within = std::isfinite(errors[k]) && errors[k] <= tolerance;
        if (!within)
            since = -1;
        else if (since < 0)
            since = int(k) + 1;
    }
    return since;
}

} // namespace ssgi::stability
