// The figures of figures.h.

#include "stability/figures.h"

namespace ssgi::stability::detail {

double mean(const std::vector<double>& v, size_t from, size_t to) {
    double sum = 0.0;
    size_t n = 0;
    for (size_t i = from; i < std::min(to, v.size()); ++i)
        if (std::isfinite(v[i])) sum += v[i], ++n;
    return n ? sum / double(n) : kNaN;
}

Mask regionMask(const Case& c, const View& start, const View& before, const View& end,
                const Scene& scene) {
    const Pixels& oldHdr = start.hdr;
    switch (c.region) {
    case Region::Disoccluded:
        return disoccludedMask(start, end);
    case Region::Carried:
        return subtract(geometryMask(end), unseenMask(before, end));
    case Region::Thin:
        return thinMask(end, 3, 1.15f, 1);
    case Region::NearOccluder:
        return nearBoxMask(end, c.occluder, aoRadius(scene));
    case Region::LightChanged:
    case Region::ObjectChanged:
        return changedMask(oldHdr, end.hdr, geometryMask(end), 0.2);
    case Region::Grazing:
        return grazingMask(end, 0.2f);
    case Region::DepthEdges:
        return depthEdgeMask(end, 1.2f, 2);
    case Region::Geometry:
        return geometryMask(end);
    }
    return {};
}

namespace {

// The region and its pixel counts; a cut's region is the pixels whose history it kept.
void takeRegion(CaseResult& res, const Case& c, const Scene& scene, const TestedRun& tested,
                const View& converged) {
    res.region = c.region == Region::Carried
                     ? tested.keptAtChange
                     : regionMask(c, tested.start, tested.before, converged, scene);
    res.geometryPixels = metrics::countInside(geometryMask(converged));
    if (c.region == Region::Carried) { // kept, though the camera before could not see it
        const Mask unseen = unseenMask(tested.before, converged);
        size_t invented = 0;
        for (size_t i = 0; i < unseen.size(); ++i)
            invented += unseen[i] && tested.keptAtChange[i];
        res.keptUnseen = double(invented) / double(res.geometryPixels);
    }
    res.regionPixels = metrics::countInside(res.region);
}

// Each frame's errors from the last change on.
struct FrameErrors {
    std::vector<double> region; // the tested renderer's, in the region
    std::vector<double> rest;   // outside it; a resize: the unresized timeline's, in the region
    std::vector<double> fresh;  // the fresh renderer's at the same age, in the region
};

// Fills the errors and stale fractions of the frames from the last change on, and staleAfter.
FrameErrors measureFrameErrors(CaseResult& res, const Case& c, size_t lastChange,
                               const TestedRun& tested, const std::vector<Pixels>& unresized,
                               const FreshRun& fresh, const View& converged) {
    const Mask rest = subtract(geometryMask(converged), res.region);
    const std::vector<Pixels>& after = tested.after;
    FrameErrors e;
    for (size_t k = 0; k < after.size(); ++k) {
        FrameRecord& rec = res.frames[lastChange + k];
        rec.error = maskedRelMse(after[k], converged.hdr, res.region);
        rec.errorRest = k < unresized.size() ? maskedRelMse(unresized[k], converged.hdr, res.region)
                                             : maskedRelMse(after[k], converged.hdr, rest);
        if (k < fresh.frames.size()) {
            rec.freshError = maskedRelMse(fresh.frames[k], converged.hdr, res.region);
            rec.freshRest = maskedRelMse(fresh.frames[k], converged.hdr, rest);
        }
        if (c.movesLight || c.region == Region::ObjectChanged)
            rec.stale = staleFraction(after[k], tested.start.hdr, converged.hdr, res.region);
        e.region.push_back(rec.error), e.rest.push_back(rec.errorRest);
        e.fresh.push_back(rec.freshError);
        if (k > 0 && std::isfinite(rec.stale))
            res.staleAfter =
                std::isfinite(res.staleAfter) ? std::max(res.staleAfter, rec.stale) : rec.stale;
    }
    return e;
}

// Mean of the last 4 entries of v[0, count).
double meanOfLast4(const std::vector<double>& v, size_t count) {
    return mean(v, count - std::min<size_t>(4, count), count);
}

// Where the errors settle: the region's, the rest's and the fresh renderer's.
void measureSettledErrors(CaseResult& res, const FrameErrors& e, size_t freshFrames) {
    res.convergedError = meanOfLast4(e.region, e.region.size());
    res.restError = meanOfLast4(e.rest, e.rest.size());
    res.ghostLeft = res.convergedError / res.restError;
    res.freshSettledError = meanOfLast4(e.fresh, freshFrames);
}

// Recovered: the region's error within twice that of the rest of the same frame, whose history
// the change left alone (so motion's own damage is not charged to the region), or within twice
// a fresh start's at the same age, whichever is larger (once the camera holds still the rest
// accumulates again too, and a region as good as a fresh start has nothing left to recover). A
// resize's region is the whole image: its "rest" is the same frame of the timeline rendered at
// the final size throughout (the motion's damage without the resize's); where there is no rest
// at all, within twice where a fresh start settles.
void measureRecovery(CaseResult& res, const FrameErrors& e) {
    const double freshSettled = res.freshSettledError;
    std::vector<double> relative;
    for (size_t k = 0; k < e.region.size(); ++k) {
        double tolerance = 2.0 * (std::isfinite(e.rest[k]) ? e.rest[k] : freshSettled);
        // The fresh start renders `converge` frames, one fewer than the hold's after the change:
        // past them it has settled.
        const double fresh = std::isfinite(e.fresh[k]) ? e.fresh[k] : freshSettled;
        if (std::isfinite(e.rest[k]) && std::isfinite(fresh))
            tolerance = std::max(tolerance, 2.0 * fresh);
        relative.push_back(e.region[k] / tolerance);
    }
    res.tolerance = 2.0 * (std::isfinite(res.restError) ? res.restError : freshSettled);
    // An empty region (a cut that kept no history) has nothing to recover.
    res.recoveryFrames = res.regionPixels == 0 ? 0 : framesUntilWithin(relative, 1.0);
}

// The region's mean error over the first 8 frames after the change, over the fresh start's and
// (a resize) over the unresized timeline's.
void measureExcess(CaseResult& res, const FrameErrors& e, bool resized) {
    res.excessOverFresh = mean(e.region, 0, 8) / mean(e.fresh, 0, 8) - 1.0;
    if (resized) res.excessOverUnresized = mean(e.region, 0, 8) / mean(e.rest, 0, 8) - 1.0;
}

double meanPathFlicker(const std::vector<FrameRecord>& frames) {
    std::vector<double> pathFlicker;
    for (const FrameRecord& rec : frames)
        if (std::string(rec.phase) == "path") pathFlicker.push_back(rec.flicker);
    return mean(pathFlicker, 0, pathFlicker.size());
}

} // namespace

void measureFigures(CaseResult& res, const Case& c, const Scene& scene, size_t lastChange,
                    const TestedRun& tested, const std::vector<Pixels>& unresized,
                    const FreshRun& fresh, const View& converged) {
    takeRegion(res, c, scene, tested, converged);
    const FrameErrors errors =
        measureFrameErrors(res, c, lastChange, tested, unresized, fresh, converged);
    measureSettledErrors(res, errors, fresh.frames.size());
    measureRecovery(res, errors);
    measureExcess(res, errors, !unresized.empty());
    res.stillFlicker = mean(fresh.stillFlicker, 0, fresh.stillFlicker.size());
    res.pathFlicker = meanPathFlicker(res.frames);
}

} // namespace ssgi::stability::detail
