// Compensated summation of the per-pixel sums. A float32 running sum of N samples of a constant c
// drifts by about N eps |c| / 2 (a constant pixel's mean was off by 2.5e-4 relative at 32k spp);
// keeping each sum as an unevaluated pair of floats hi + lo ("double-float" arithmetic: Dekker 1971,
// "A floating-point technique for extending the available precision"; Higham, "Accuracy and
// Stability of Numerical Algorithms", sec. 4.3) makes it about as exact as a sum in double, on any
// device, float64 support or not.
// The host reads the sum as double(hi) + double(lo).
#ifndef VKP_COMPENSATED_SUM_H
#define VKP_COMPENSATED_SUM_H
#include "glsl_compat.h"

VKP_BEGIN

/// Adds x to the double-float sum (hi, lo), component-wise: hi + lo carries about 48 significant
/// bits. Knuth's TwoSum gives the exact rounding error of hi + x (Knuth, TAOCP vol. 2, 4.2.2,
/// theorem B; branch-free, valid for any magnitudes); it is folded into lo and the pair is
/// renormalised by a second TwoSum, so |lo| <= ulp(hi) / 2 always. Without the renormalisation lo
/// itself grows like n eps |sum| and its own rounding ruins the sum after ~10^6 additions (plain
/// Neumaier/Kahan: tests/unit/test_compensated_sum.cpp). Each addition errs by ~eps^2 |sum|
/// (eps = 2^-24), so n additions err by <= ~n eps^2 relative (3.6e-9 at n = 10^6).
/// Every step is VKP_PRECISE: a compiler that rewrote (s - a) - ... algebraically would silently
/// turn this into a plain sum.
VKP_FN void addCompensated(INOUT(vec4) hi, INOUT(vec4) lo, vec4 x) {
    VKP_PRECISE vec4 s = hi + x;
    VKP_PRECISE vec4 bp = s - hi;
    VKP_PRECISE vec4 e = (hi - (s - bp)) + (x - bp);  // s + e == hi + x exactly
    VKP_PRECISE vec4 l = lo + e;
    VKP_PRECISE vec4 s2 = s + l;
    VKP_PRECISE vec4 bp2 = s2 - s;
    VKP_PRECISE vec4 e2 = (s - (s2 - bp2)) + (l - bp2);  // s2 + e2 == s + l exactly
    hi = s2;
    lo = e2;
}

VKP_END
#endif
