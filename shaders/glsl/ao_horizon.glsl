// Horizon-based AO (GTAO, Jimenez et al. 2016): in each of DIRECTIONS screen-space slices
// through p, march both ways to find the highest horizon within the AO radius, then integrate
// the cosine-weighted visible arc between the two horizons analytically. This estimates the
// same quantity as the reference's AO (cosine-weighted visibility within the radius).
float horizonAo(vec2 center, vec3 p, vec3 n, float radius, float radiusPixels, float rotation) {
    vec3 viewVector = normalize(frame.cameraPosition.xyz - p);
    float visibility = 0.0;
    for (int d = 0; d < DIRECTIONS; ++d) {
        float angle = rotation + PI * float(d) / float(DIRECTIONS);
        vec2 direction = vec2(cos(angle), sin(angle)); // pixels, y down
        vec3 sliceDirection = normalize(cameraRight() * direction.x - cameraUp() * direction.y);
        vec3 ortho = normalize(sliceDirection - dot(sliceDirection, viewVector) * viewVector);
        vec3 axis = normalize(cross(ortho, viewVector));
        vec3 projectedNormal = n - axis * dot(n, axis);
        float projectedLength = length(projectedNormal);
        if (projectedLength < 1e-4) continue;
        float cosN = clamp(dot(projectedNormal, viewVector) / projectedLength, 0.0, 1.0);
        float angleN = sign(dot(ortho, projectedNormal)) * acos(cosN);
        float lowest[2] = float[2](cos(angleN + 0.5 * PI), cos(angleN - 0.5 * PI));
        // The tangent plane's line in the slice, toward the first side (side_sign 1).
        vec3 tangent = ortho * cosN - viewVector * sin(angleN);
        float horizon[2] = lowest;
        for (int side = 0; side < 2; ++side) {
            float side_sign = side == 0 ? 1.0 : -1.0;
            for (int i = 0; i < STEPS; ++i) {
                float t = (float(i) + 0.5) / float(STEPS);
                vec2 samplePixel = center + side_sign * direction * max(t * t * radiusPixels, 1.0 + float(i));
                if (!insideViewport(samplePixel)) break;
                vec4 q = positionAt(samplePixel);
                if (q.w == 0.0) continue;
                vec3 toSample = q.xyz - p;
                float distance = length(toSample);
                if (distance < 1e-6 * radius) continue;
                // Samples fade out over the last tenth of the radius, beyond which they are open.
                float weight = clamp((radius - distance) / (0.1 * radius), 0.0, 1.0);
                // The sample's angle in the slice, from its height above p's tangent plane and
                // its length along the slice's tangent. A sample's pixel centre lies off the
                // slice by up to half a pixel: its direction's angle from the view vector lifted a
                // flat floor's horizons above the tangent, and the bunny's grazing floor had an
                // AO of 0.95-0.97 in stripes. Measured from the plane, a sample on it is at the
                // tangent wherever it lies; one in the slice is where it was.
                float height = dot(toSample, n) / projectedLength;
                float along = dot(toSample, side_sign * tangent);
                float length2 = max(height * height + along * along, 1e-12 * radius * radius);
                float cosSample = (lowest[side] * along + cosN * height) * inversesqrt(length2);
                float cosHorizon = mix(lowest[side], cosSample, weight);
                horizon[side] = max(horizon[side], cosHorizon);
            }
        }
        float h0 = angleN + clamp(-acos(horizon[1]) - angleN, -0.5 * PI, 0.5 * PI);
        float h1 = angleN + clamp(acos(horizon[0]) - angleN, -0.5 * PI, 0.5 * PI);
        float arc0 = (cosN + 2.0 * h0 * sin(angleN) - cos(2.0 * h0 - angleN)) * 0.25;
        float arc1 = (cosN + 2.0 * h1 * sin(angleN) - cos(2.0 * h1 - angleN)) * 0.25;
        visibility += projectedLength * (arc0 + arc1);
    }
    return visibility / float(DIRECTIONS);
}
