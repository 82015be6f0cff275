#version 460
// The denoiser's kernel (host/render/denoiser.cpp), on demodulated radiance guided by the per-pixel
// variance and the feature images: by default one pass of non-local means with feature weights
// (PASS 2, below); or edge-avoiding a-trous wavelets, the spatial filter of SVGF (Schied et al.
// 2017, "Spatiotemporal Variance-Guided Filtering: Real-Time Reconstruction for Path-Traced Global
// Illumination", sec. 4.4-4.5) built on the a-trous transform of Dammertz et al. 2010
// ("Edge-Avoiding A-Trous Wavelet Transform for fast Global Illumination Filtering").
//
// Three passes, chosen by the specialization constant PASS (so none carries another's code:
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
//  PASS 2, non-local means (Rousselle, Knaus and Zwicker 2012, "Adaptive Rendering with Non-Local
//          Means Filtering", sec. 4-5): every pixel of the (2 radius + 1)^2 window around the
//          centre is a tap, weighted by how alike the 3x3 patches around the two are, in units of
//          their variances, times the same normal and depth edge-stopping as PASS 1 (the feature
//          weights of Rousselle, Manzi and Zwicker 2013), and a tap brighter than the centre by
//          its excess in units of the centre's median-limited standard deviation (as PASS 1's
//          brighter taps). The output is the same local linear fit as PASS 1's (taps in pixels),
//          and its variance; it is the first level, the a-trous levels of step 2, 4, ... follow.
//
// Data: every buffer holds one vec4 per pixel of the band, row-major, `push.width` wide and
// `push.rows` rows (row 0 = the band's top). Bindings:
//  0 color     (rgb, -)                     uniform texel buffer RGBA32F
//  1 variance  (rgb: variance of the mean)  uniform texel buffer RGBA32F
//  2 albedo    (rgb, -)                     uniform texel buffer RGBA32F
//  3 guide     (normal or 0, depth)         uniform texel buffer RGBA32F; depth < 0: nothing hit; the
//                                           normal's length is 1 / (1 + its direction's variance)
//  4 illumIn   (demodulated rgb, var_L)     uniform texel buffer RGBA32F (PASS 1, 2)
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
    uint remodulate;  // PASS 1, 2: 1 = multiply by the albedo (the last level)
    float sigmaL;     // PASS 1: luminance: standard deviations of the centre that give weight 1/e
    float sigmaN;     // normal: exponent of the cosine
    float sigmaZ;     // depth: multiples of the depth change the gradient predicts that give 1/e
    float albedoEps;  // the albedo's floor for demodulation
    float ridge;      // PASS 1, 2: >= 0: local linear fit with this ridge on the slopes; < 0: weighted mean
    float normalNoise;  // PASS 1, 2: > 0: the cosine's exponent is min(sigmaN, normalNoise / (theta_p^2 + theta_q^2))
    float fireflyBound;  // PASS 0: > 0: a pixel's demodulated luminance is at most the largest of its
                         // 8 neighbours' plus fireflyBound of their standard deviations
    uint radius;      // PASS 2: the window reaches this many pixels from the centre
    float patchK;     // PASS 2: patch distances in units of patchK^2 x the two pixels' variances
    float brighterSigma;  // PASS 2: a brighter tap's excess in units of this x the centre's standard deviation
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

/// What the feature weights compare every tap with: the centre's guide, read once per output pixel.
struct Centre {
    bool hit;        // some sample of the pixel hit a surface (depth >= 0)
    vec4 g;          // the guide: normal (0: none; length 1 / (1 + theta^2)), depth
    float lenP;      // |normal|
    float thetaP2;   // the variance of the normal's direction (rad^2)
    vec2 grad;       // depth change per pixel along x and y
    float zEps;      // depth tolerance: rounding on a flat face never stops the filter
};

Centre centreOf(int x, int y, int i) {
    Centre c;
    c.g = texelFetch(uGuide, i);
    c.hit = c.g.w >= 0.0;
    c.lenP = length(c.g.xyz);  // 0: no normal; else 1 / (1 + theta_p^2), its direction's variance (host)
    c.thetaP2 = c.lenP > 0.0 ? 1.0 / c.lenP - 1.0 : 0.0;
    c.grad = c.hit ? depthGradient(x, y, c.g.w) : vec2(0.0);
    c.zEps = max(1e-3 * c.g.w, 1e-30);  // relative
    return c;
}

/// Log of the feature part of a tap's weight (SVGF eq. 3-4), the tap `offset` pixels from the
/// centre with guide gq: depth against the change the centre's gradient predicts; normals by the
/// cosine of their directions, its exponent lowered where the two mean normals are noisy
/// (DenoiseOptions::normalNoise); -1e30 where a hit meets a miss or a normal meets none (two hits
/// without a normal, a mean normal of 0, are alike).
float featureLogWeight(Centre c, vec2 offset, vec4 gq) {
    if (c.hit != (gq.w >= 0.0)) return -1e30;  // a hit and a miss never mix
    if (!c.hit) return 0.0;
    float expected = abs(dot(c.grad, offset));
    float logW = -abs(c.g.w - gq.w) / (push.sigmaZ * expected + c.zEps);
    float lenQ = length(gq.xyz);
    if (c.lenP > 0.0 && lenQ > 0.0) {
        float theta2 = c.thetaP2 + (1.0 / lenQ - 1.0);
        float sN = push.normalNoise > 0.0 ? min(push.sigmaN, push.normalNoise / max(theta2, 1e-30)) : push.sigmaN;
        logW += sN * log(max(dot(c.g.xyz, gq.xyz) / (c.lenP * lenQ), 1e-30));
    } else if (c.lenP > 0.0 || lenQ > 0.0) {
        logW = -1e30;
    }
    return logW;
}

/// The sums of a pass's weighted taps: for the weighted mean and for the local linear fit, the
/// plane b0 + b1 u1 + b2 u2 through the taps at offsets (u1, u2), and for its variance.
struct Fit {
    vec3 sum, sumX, sumY;                  // sum w q, sum w u1 q, sum w u2 q
    float sumW, m01, m02, m11, m12, m22;   // moments of w u u^T, u = (1, u1, u2)
    float sumVar, r01, r02, r11, r12, r22; // of w^2 var u u^T
};

Fit fitZero() {
    return Fit(vec3(0.0), vec3(0.0), vec3(0.0), 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
}

/// Adds tap q (demodulated rgb, variance of its luminance) with weight wq at offset (u1, u2).
void fitAdd(inout Fit f, float wq, float u1, float u2, vec4 q) {
    float wv = wq * wq * q.w;
    f.sum += wq * q.rgb;
    f.sumX += wq * u1 * q.rgb;
    f.sumY += wq * u2 * q.rgb;
    f.sumW += wq;
    f.m01 += wq * u1; f.m02 += wq * u2; f.m11 += wq * u1 * u1; f.m12 += wq * u1 * u2; f.m22 += wq * u2 * u2;
    f.sumVar += wv;
    f.r01 += wv * u1; f.r02 += wv * u2; f.r11 += wv * u1 * u1; f.r12 += wv * u1 * u2; f.r22 += wv * u2 * u2;
}

/// The centre's value and its variance from the taps: their weighted mean (push.ridge < 0) or the
/// plane's b0. f.sumW > 0: the centre always weighs > 0.
vec4 fitSolve(Fit f) {
    if (push.ridge < 0.0) return vec4(f.sum / f.sumW, f.sumVar / (f.sumW * f.sumW));
    // The first row of the inverse of the symmetric moment matrix M + ridge sum(w) diag(0,1,1)
    // (positive definite: sumW > 0), by cofactors.
    float a11 = f.m11 + push.ridge * f.sumW, a22 = f.m22 + push.ridge * f.sumW;
    float c0 = a11 * a22 - f.m12 * f.m12, c1 = f.m02 * f.m12 - f.m01 * a22, c2 = f.m01 * f.m12 - a11 * f.m02;
    vec3 e = vec3(c0, c1, c2) / (f.sumW * c0 + f.m01 * c1 + f.m02 * c2);
    vec3 rgb = max(e.x * f.sum + e.y * f.sumX + e.z * f.sumY, vec3(0.0));  // negative taps can undershoot 0
    float var = e.x * e.x * f.sumVar + e.y * e.y * f.r11 + e.z * e.z * f.r22 +
                2.0 * (e.x * e.y * f.r01 + e.x * e.z * f.r02 + e.y * e.z * f.r12);
    return vec4(rgb, var);
}

/// The centre's variance for the luminance edge-stopping: x, its 3x3 blur (SVGF eq. 5: a single
/// pixel's variance estimate is itself noisy); y, the smaller of that and the median of the nine
/// variances (edge pixels repeated), the scale for taps brighter than the centre: one very bright
/// neighbour (the sun seen through glass in a few pixels) dominates the blur and would let a dark
/// pixel take its light in, a halo that relMSE weighs heavily; the median ignores up to four such
/// neighbours.
vec2 centreVariances(int x, int y) {
    const int w = int(push.width), h = int(push.rows);
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
    return vec2(varBlur, min(varBlur, median9(v9)));
}

void atrousLevel(int x, int y, int i) {
    const int w = int(push.width), h = int(push.rows);
    // The centre's luminance scale: sigmaL x the standard deviation of its blurred variance; for a
    // tap brighter than the centre, of the median-limited one. Darker taps keep the blurred scale,
    // so a bright outlier is still pulled towards its neighbours. A tiny floor keeps 0/0 out where
    // the variance is 0: equal luminances weigh 1, others 0.
    vec2 v = centreVariances(x, y);
    float lumScale = 1.0 / (push.sigmaL * sqrt(max(v.x, 0.0)) + 1e-20);
    float lumScaleBrighter = 1.0 / (push.sigmaL * sqrt(max(v.y, 0.0)) + 1e-20);

    Centre c = centreOf(x, y, i);
    float lumP = dot(kLuma, texelFetch(uIllumIn, i).rgb);
    const float kB3[5] = float[5](1.0 / 16.0, 1.0 / 4.0, 3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0);
    Fit f = fitZero();
    const int s = int(push.step);
    for (int ty = -2; ty <= 2; ++ty)
        for (int tx = -2; tx <= 2; ++tx) {
            int qx = x + tx * s, qy = y + ty * s;
            if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
            int j = qy * w + qx;
            vec4 q = texelFetch(uIllumIn, j);
            // Log of the edge-stopping weight (SVGF eq. 2-5), one exp per tap.
            float lumQ = dot(kLuma, q.rgb);
            float logW = -abs(lumP - lumQ) * (lumQ > lumP ? lumScaleBrighter : lumScale) +
                         featureLogWeight(c, vec2(float(tx * s), float(ty * s)), texelFetch(uGuide, j));
            fitAdd(f, kB3[tx + 2] * kB3[ty + 2] * exp(logW), float(tx), float(ty), q);
        }
    vec4 result = fitSolve(f);
    if (push.remodulate != 0u) result.rgb *= demodAlbedo(i);
    illumOut[i] = result;
}

/// PASS 2's texel of pixel (qx, qy) of the demodulated image, (rgb, variance); variance -1
/// outside the band.
vec4 illumTexel(int qx, int qy) {
    if (qx < 0 || qy < 0 || qx >= int(push.width) || qy >= int(push.rows)) return vec4(0.0, 0.0, 0.0, -1.0);
    return texelFetch(uIllumIn, qy * int(push.width) + qx);
}

/// A texel as a patch pixel: (luminance, variance).
vec2 lumVar(vec4 t) { return vec2(dot(kLuma, t.rgb), t.w); }

/// PASS 2's patch pixel (qx, qy): (luminance, variance), or (0, -1) outside the band.
vec2 patchTexel(int qx, int qy) { return lumVar(illumTexel(qx, qy)); }

/// One pixel pair of two patches (Rousselle et al. 2012, eq. 8 with alpha = 1): the squared
/// difference of the luminances less what their variances explain, in units of
/// patchK^2 (var_p + var_q); 0 where either pixel is outside the band.
float pairDistance(vec2 p, vec2 q) {
    if (p.y < 0.0 || q.y < 0.0) return 0.0;
    return ((p.x - q.x) * (p.x - q.x) - (p.y + min(p.y, q.y))) / (1e-20 + push.patchK * push.patchK * (p.y + q.y));
}

void nonLocalMeans(int x, int y, int i) {
    const int w = int(push.width), h = int(push.rows), r = int(push.radius);
    Centre c = centreOf(x, y, i);
    // The centre's patch, p[(dy + 1) * 3 + dx + 1] for the pixel (x + dx, y + dy); p[4] the centre.
    vec2 p[9];
    for (int n = 0; n < 9; ++n) p[n] = patchTexel(x + n % 3 - 1, y + n / 3 - 1);
    // A tap brighter than the centre also pays its excess in units of brighterSigma x the
    // centre's median-limited standard deviation (centreVariances): the patches of a dark pixel
    // beside a few very bright, very noisy ones (the sun seen through glass) are alike within
    // those pixels' variance, and would let the dark pixel take their light in.
    float brighterScale = 1.0 / (push.brighterSigma * sqrt(max(centreVariances(x, y).y, 0.0)) + 1e-20);
    Fit f = fitZero();
    for (int ty = -r; ty <= r; ++ty) {
        int qy = y + ty;
        // The tap's patch by columns, left (a), middle (b) and right (m), rows qy - 1 .. qy + 1;
        // each tap to the right reads one new column. The middle row's texel is kept whole
        // (bq, mq): the middle column's is the tap itself.
        vec2 a0 = patchTexel(x - r - 1, qy - 1), a1 = patchTexel(x - r - 1, qy), a2 = patchTexel(x - r - 1, qy + 1);
        vec4 bq = illumTexel(x - r, qy);
        vec2 b0 = patchTexel(x - r, qy - 1), b1 = lumVar(bq), b2 = patchTexel(x - r, qy + 1);
        for (int tx = -r; tx <= r; ++tx) {
            int qx = x + tx;
            vec4 mq = illumTexel(qx + 1, qy);
            vec2 m0 = patchTexel(qx + 1, qy - 1), m1 = lumVar(mq), m2 = patchTexel(qx + 1, qy + 1);
            if (qx >= 0 && qy >= 0 && qx < w && qy < h) {
                float d = (pairDistance(p[0], a0) + pairDistance(p[1], b0) + pairDistance(p[2], m0) +
                           pairDistance(p[3], a1) + pairDistance(p[4], b1) + pairDistance(p[5], m1) +
                           pairDistance(p[6], a2) + pairDistance(p[7], b2) + pairDistance(p[8], m2)) / 9.0;
                float logW = -max(d, 0.0) - max(b1.x - p[4].x, 0.0) * brighterScale +
                             featureLogWeight(c, vec2(float(tx), float(ty)), texelFetch(uGuide, qy * w + qx));
                fitAdd(f, exp(logW), float(tx), float(ty), bq);
            }
            a0 = b0; a1 = b1; a2 = b2;
            b0 = m0; b1 = m1; b2 = m2;
            bq = mq;
        }
    }
    vec4 result = fitSolve(f);
    if (push.remodulate != 0u) result.rgb *= demodAlbedo(i);
    illumOut[i] = result;
}

void main() {
    int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
    if (x >= int(push.width) || y >= int(push.rows)) return;
    int i = y * int(push.width) + x;
    if (PASS == 0u) demodulate(x, y, i);
    else if (PASS == 1u) atrousLevel(x, y, i);
    else nonLocalMeans(x, y, i);
}
