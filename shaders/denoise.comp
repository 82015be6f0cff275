#version 460
// The denoiser's kernel (host/render/denoiser.cpp): edge-avoiding a-trous wavelets guided by the
// per-pixel variance, on demodulated radiance; the spatial filter of SVGF (Schied et al. 2017,
// "Spatiotemporal Variance-Guided Filtering: Real-Time Reconstruction for Path-Traced Global
// Illumination", sec. 4.4-4.5) built on the a-trous transform of Dammertz et al. 2010
// ("Edge-Avoiding A-Trous Wavelet Transform for fast Global Illumination Filtering").
//
// Two passes, chosen by the specialization constant PASS (so neither carries the other's code:
// on lavapipe a branch never skips, design.md "Every reachable branch runs"):
//  PASS 0, demodulate: out = (color / a, var_L) with a = max(albedo, eps) per channel and var_L the
//          variance of the demodulated luminance (channels taken as fully correlated: the standard
//          deviations add), from the variance of the pixel's mean. With push.fireflyBound > 0 a
//          firefly is scaled down first: a pixel brighter than each of its 8 neighbours' value
//          plus fireflyBound of their standard deviations, by no more than fireflyBound of its own.
//  PASS 1, one a-trous level of step 2^level: a 5x5 B3-spline kernel with holes, each tap weighted
//          by the edge-stopping functions of SVGF eq. 2-5 on normal, depth and luminance (the
//          latter in units of sigmaL x the 3x3-blurred standard deviation of the centre, for a
//          tap brighter than the centre the smaller of that and the 3x3 median's); the
//          variance is carried along, var' = sum w^2 var / (sum w)^2 (SVGF eq. 3). With
//          push.remodulate the output is multiplied back by a (the last level).
//          With push.ridge >= 0 a level is a local linear fit instead of a weighted mean: the
//          output is b0 of the weighted least-squares plane b0 + b1 tx + b2 ty through the taps
//          (tx, ty in taps), the ridge adding ridge x sum(w) to the slopes' diagonal so a tap row
//          along an edge still solves. A weighted mean whose window an edge cuts on one side is
//          biased by the gradient times the window's offset; the plane is not (the boundary bias
//          of kernel regression; Fan and Gijbels 1996, "Local Polynomial Modelling", sec. 3.2.5).
//          Its variance is e^T (sum w^2 var u u^T) e with e the first row of the inverse moment
//          matrix and u = (1, tx, ty).
//
// Data: every buffer holds one vec4 per pixel of the band, row-major, `push.width` wide and
// `push.rows` rows (row 0 = the band's top). Bindings:
//  0 color     (rgb, -)                     uniform texel buffer RGBA32F
//  1 variance  (rgb: variance of the mean)  uniform texel buffer RGBA32F
//  2 albedo    (rgb, -)                     uniform texel buffer RGBA32F
//  3 guide     (normal or 0, depth)         uniform texel buffer RGBA32F; depth < 0: nothing hit; the
//                                           normal's length is 1 / (1 + its direction's variance)
//  4 illumIn   (demodulated rgb, var_L)     uniform texel buffer RGBA32F (PASS 1)
//  5 illumOut  same layout                  storage buffer
// Taps outside the band are skipped and the weights renormalised, so a band's rows farther than
// the filter's radius from its ends are the same bits as those of a single pass.
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 8, local_size_y = 8) in;

layout(constant_id = 0) const uint PASS = 0u;

layout(set = 0, binding = 0) uniform samplerBuffer uColor;
layout(set = 0, binding = 1) uniform samplerBuffer uVariance;
layout(set = 0, binding = 2) uniform samplerBuffer uAlbedo;
layout(set = 0, binding = 3) uniform samplerBuffer uGuide;
layout(set = 0, binding = 4) uniform samplerBuffer uIllumIn;
layout(std430, set = 0, binding = 5) writeonly buffer IllumOut { vec4 illumOut[]; };

layout(push_constant) uniform Push {
    uint width;       // pixels per row
    uint rows;        // rows of the band
    uint step;        // PASS 1: distance between taps, 2^level pixels
    uint remodulate;  // PASS 1: 1 = multiply by the albedo (the last level)
    float sigmaL;     // luminance: standard deviations of the centre that give weight 1/e
    float sigmaN;     // normal: exponent of the cosine
    float sigmaZ;     // depth: multiples of the depth change the gradient predicts that give 1/e
    float albedoEps;  // the albedo's floor for demodulation
    float ridge;      // PASS 1: >= 0: local linear fit with this ridge on the slopes; < 0: weighted mean
    float normalNoise;  // PASS 1: > 0: the cosine's exponent is min(sigmaN, normalNoise / (theta_p^2 + theta_q^2))
    float fireflyBound;  // PASS 0: > 0: a pixel's demodulated luminance is at most the largest of its
                         // 8 neighbours' plus fireflyBound of their standard deviations
} push;

const vec3 kLuma = vec3(0.2126, 0.7152, 0.0722);  // Rec. 709 luminance

vec3 demodAlbedo(int i) { return max(texelFetch(uAlbedo, i).rgb, vec3(push.albedoEps)); }

/// Depth change per pixel along x and y at (x, y): of the two one-sided differences the smaller
/// (so a neighbour across a depth edge does not make the gradient steep); 0 beside misses.
vec2 depthGradient(int x, int y, float z) {
    vec2 g = vec2(0.0);
    for (int axis = 0; axis < 2; ++axis) {
        float best = 0.0;
        bool found = false;
        for (int s = -1; s <= 1; s += 2) {
            int qx = axis == 0 ? x + s : x, qy = axis == 1 ? y + s : y;
            if (qx < 0 || qy < 0 || qx >= int(push.width) || qy >= int(push.rows)) continue;
            float zq = texelFetch(uGuide, qy * int(push.width) + qx).w;
            if (zq < 0.0) continue;
            float d = (zq - z) * float(s);
            if (!found || abs(d) < abs(best)) best = d;
            found = true;
        }
        g[axis] = best;
    }
    return g;
}

/// Pixel j's demodulated colour (in `c`) and the standard deviation of its luminance (channels
/// fully correlated).
float demodulated(int j, out vec3 c) {
    vec3 a = demodAlbedo(j);
    c = texelFetch(uColor, j).rgb / a;
    return dot(kLuma, sqrt(max(texelFetch(uVariance, j).rgb, vec3(0.0))) / a);
}

void demodulate(int x, int y, int i) {
    vec3 c;
    float sdL = demodulated(i, c);
    if (push.fireflyBound > 0.0) {
        // A firefly (one rare, bright sample in a pixel) is brighter than every neighbour's value
        // plus fireflyBound of that neighbour's standard deviations: scaled down to that bound.
        float bound = -1.0;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                int qx = x + dx, qy = y + dy;
                if ((dx == 0 && dy == 0) || qx < 0 || qy < 0 || qx >= int(push.width) || qy >= int(push.rows)) continue;
                vec3 cq;
                float sq = demodulated(qy * int(push.width) + qx, cq);
                bound = max(bound, dot(kLuma, cq) + push.fireflyBound * sq);
            }
        // Only within the pixel's own noise: a bright pixel it is sure of (a small highlight,
        // converged) is kept, whatever its neighbours.
        float lum = dot(kLuma, c);
        if (bound >= 0.0 && lum > bound && lum - bound <= push.fireflyBound * sdL) c *= bound / lum;
    }
    illumOut[i] = vec4(c, sdL * sdL);
}

/// The median of nine values: the 19 compare-exchanges of the median network in Paeth, "Median
/// Finding on a 3x3 Grid" (Graphics Gems, 1990); v is left partly sorted.
float median9(inout float v[9]) {
#define VKP_SORT2(a, b) { float lo = min(v[a], v[b]); v[b] = max(v[a], v[b]); v[a] = lo; }
    VKP_SORT2(1, 2) VKP_SORT2(4, 5) VKP_SORT2(7, 8) VKP_SORT2(0, 1) VKP_SORT2(3, 4) VKP_SORT2(6, 7)
    VKP_SORT2(1, 2) VKP_SORT2(4, 5) VKP_SORT2(7, 8) VKP_SORT2(0, 3) VKP_SORT2(5, 8) VKP_SORT2(4, 7)
    VKP_SORT2(3, 6) VKP_SORT2(1, 4) VKP_SORT2(2, 5) VKP_SORT2(4, 7) VKP_SORT2(4, 2) VKP_SORT2(6, 4)
    VKP_SORT2(4, 2)
#undef VKP_SORT2
    return v[4];
}

void atrousLevel(int x, int y, int i) {
    const int w = int(push.width), h = int(push.rows);
    // The centre's luminance scale: sigmaL x the standard deviation, its variance blurred 3x3
    // (SVGF eq. 5: a single pixel's variance estimate is itself noisy). A tap brighter than the
    // centre is judged by the smaller of that blurred variance and the median of the nine
    // variances (edge pixels repeated): one very bright neighbour (the sun seen through glass in a
    // few pixels) dominates the blur and would let a dark pixel take its light in, a halo that
    // relMSE weighs heavily; the median ignores up to four such neighbours. Darker taps keep the
    // blurred scale, so a bright outlier is still pulled towards its neighbours.
    float varBlur = 0.0, wBlur = 0.0;
    float v9[9];
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            int qx = x + dx, qy = y + dy;
            float var = texelFetch(uIllumIn, clamp(qy, 0, h - 1) * w + clamp(qx, 0, w - 1)).w;
            v9[(dy + 1) * 3 + dx + 1] = var;
            if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
            float k = (dx == 0 ? 0.5 : 0.25) * (dy == 0 ? 0.5 : 0.25);
            varBlur += k * var;
            wBlur += k;
        }
    varBlur /= wBlur;
    // A tiny floor keeps 0/0 out where the variance is 0: equal luminances weigh 1, others 0.
    float lumScale = 1.0 / (push.sigmaL * sqrt(max(varBlur, 0.0)) + 1e-20);
    float lumScaleBrighter = 1.0 / (push.sigmaL * sqrt(max(min(varBlur, median9(v9)), 0.0)) + 1e-20);

    vec4 centre = texelFetch(uIllumIn, i);
    vec4 g = texelFetch(uGuide, i);
    bool hit = g.w >= 0.0;
    float lenP = length(g.xyz);  // 0: no normal; else 1 / (1 + theta_p^2), its direction's variance (host)
    float thetaP2 = lenP > 0.0 ? 1.0 / lenP - 1.0 : 0.0;
    vec2 grad = hit ? depthGradient(x, y, g.w) : vec2(0.0);
    float lumP = dot(kLuma, centre.rgb);
    float zEps = max(1e-3 * g.w, 1e-30);  // relative: depth rounding on a flat face never stops the filter

    const float kB3[5] = float[5](1.0 / 16.0, 1.0 / 4.0, 3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0);
    vec3 sum = vec3(0.0), sumX = vec3(0.0), sumY = vec3(0.0);  // sum w q, sum w tx q, sum w ty q
    float sumW = 0.0, m01 = 0.0, m02 = 0.0, m11 = 0.0, m12 = 0.0, m22 = 0.0;  // moments of w u u^T
    float sumVar = 0.0, r01 = 0.0, r02 = 0.0, r11 = 0.0, r12 = 0.0, r22 = 0.0;  // of w^2 var u u^T
    const int s = int(push.step);
    for (int ty = -2; ty <= 2; ++ty)
        for (int tx = -2; tx <= 2; ++tx) {
            int qx = x + tx * s, qy = y + ty * s;
            if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
            int j = qy * w + qx;
            vec4 q = texelFetch(uIllumIn, j);
            vec4 gq = texelFetch(uGuide, j);
            // Log of the edge-stopping weight (SVGF eq. 2-4), one exp2 per tap.
            float lumQ = dot(kLuma, q.rgb);
            float logW = -abs(lumP - lumQ) * (lumQ > lumP ? lumScaleBrighter : lumScale);
            if (hit != (gq.w >= 0.0)) {
                logW = -1e30;  // a hit and a miss never mix
            } else if (hit) {
                float expected = abs(dot(grad, vec2(float(tx * s), float(ty * s))));
                logW -= abs(g.w - gq.w) / (push.sigmaZ * expected + zEps);
                // Two hits without a normal (a mean normal of 0) are alike; one without is not.
                // Two normals: the cosine of their directions, its exponent lowered where the two
                // mean normals are noisy (DenoiseOptions::normalNoise).
                float lenQ = length(gq.xyz);
                if (lenP > 0.0 && lenQ > 0.0) {
                    float theta2 = thetaP2 + (1.0 / lenQ - 1.0);
                    float sN = push.normalNoise > 0.0 ? min(push.sigmaN, push.normalNoise / max(theta2, 1e-30)) : push.sigmaN;
                    logW += sN * log(max(dot(g.xyz, gq.xyz) / (lenP * lenQ), 1e-30));
                } else if (lenP > 0.0 || lenQ > 0.0) {
                    logW = -1e30;
                }
            }
            float wq = kB3[tx + 2] * kB3[ty + 2] * exp(logW);
            float u1 = float(tx), u2 = float(ty), wv = wq * wq * q.w;
            sum += wq * q.rgb;
            sumX += wq * u1 * q.rgb;
            sumY += wq * u2 * q.rgb;
            sumW += wq;
            m01 += wq * u1; m02 += wq * u2; m11 += wq * u1 * u1; m12 += wq * u1 * u2; m22 += wq * u2 * u2;
            sumVar += wv;
            r01 += wv * u1; r02 += wv * u2; r11 += wv * u1 * u1; r12 += wv * u1 * u2; r22 += wv * u2 * u2;
        }
    // sumW > 0: the centre's weight is kB3[2]^2 times its normal factor, which is > 0.
    vec3 rgb;
    float var;
    if (push.ridge < 0.0) {
        rgb = sum / sumW;
        var = sumVar / (sumW * sumW);
    } else {
        // The first row of the inverse of the symmetric moment matrix M + ridge sum(w) diag(0,1,1)
        // (positive definite: sumW > 0), by cofactors.
        float a11 = m11 + push.ridge * sumW, a22 = m22 + push.ridge * sumW;
        float c0 = a11 * a22 - m12 * m12, c1 = m02 * m12 - m01 * a22, c2 = m01 * m12 - a11 * m02;
        vec3 e = vec3(c0, c1, c2) / (sumW * c0 + m01 * c1 + m02 * c2);
        rgb = max(e.x * sum + e.y * sumX + e.z * sumY, vec3(0.0));  // negative taps can undershoot 0
        var = e.x * e.x * sumVar + e.y * e.y * r11 + e.z * e.z * r22 +
              2.0 * (e.x * e.y * r01 + e.x * e.z * r02 + e.y * e.z * r12);
    }
    if (push.remodulate != 0u) rgb *= demodAlbedo(i);
    illumOut[i] = vec4(rgb, var);
}

void main() {
    int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
    if (x >= int(push.width) || y >= int(push.rows)) return;
    int i = y * int(push.width) + x;
    if (PASS == 0u) demodulate(x, y, i);
    else atrousLevel(x, y, i);
}
