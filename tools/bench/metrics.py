"""Error metrics and curve arithmetic of the benchmark harness (pure functions, unit-tested by
test_bench.py).

The metrics are those of `vkpath render --error-log` (host/render/error_metrics.h): over all pixels and
the three channels, MSE = mean((x - y)^2) and relMSE = mean((x - y)^2 / (y^2 + 0.01)).
"""
import math

import numpy as np

REL_EPSILON = 0.01


def mse(x, y):
    d = np.asarray(x, np.float64) - np.asarray(y, np.float64)
    return float(np.mean(d * d))


def relmse(x, y):
    x = np.asarray(x, np.float64)
    y = np.asarray(y, np.float64)
    return float(np.mean((x - y) ** 2 / (y * y + REL_EPSILON)))


def noise_floor(half_a, half_b):
    """The reference's own error, estimated from two independent half renders A and B (same spp,
    different seeds) whose average R = (A + B) / 2 is the reference.

    Per value, E[(A - B)^2] = 2 Var(half) and Var(R) = Var(half) / 2 = E[(A - B)^2] / 4, so the
    reference's expected MSE against the truth is mean((A - B)^2) / 4. A render X independent of R
    measures E[MSE(X, R)] = MSE(X, truth) + that floor. The relMSE floor is the same with each term
    divided by (R^2 + 0.01), as vkpath divides by the reference. Returns (mse_floor, relmse_floor).
    """
    a = np.asarray(half_a, np.float64)
    b = np.asarray(half_b, np.float64)
    r = 0.5 * (a + b)
    d2 = (a - b) ** 2 / 4.0
    return float(np.mean(d2)), float(np.mean(d2 / (r * r + REL_EPSILON)))


def interpolate_crossing(points, threshold):
    """First time at which a decreasing error curve reaches `threshold`.

    points: [(seconds, error), ...] in time order. The crossing between two logged points is
    interpolated linearly in log(seconds)-log(error) (error ~ 1/t is a straight line there).
    Returns the seconds, or None if no point is at or below the threshold.
    """
    prev = None
    for t, e in points:
        if e <= threshold:
            if prev is None or prev[1] <= e or prev[0] <= 0 or t <= 0 or e <= 0:
                return t
            lt0, lt1 = math.log(prev[0]), math.log(t)
            le0, le1 = math.log(prev[1]), math.log(e)
            f = (math.log(threshold) - le0) / (le1 - le0)
            return math.exp(lt0 + f * (lt1 - lt0))
        prev = (t, e)
    return None


def extrapolate_crossing(t_last, e_last, t_start, threshold):
    """Time at which an unbiased Monte Carlo error, e(t) ~ 1 / (t - t_start) once sampling has
    started at t_start, falls to `threshold` from its last value e_last at t_last. None if it cannot
    be extrapolated (no positive error or time)."""
    if e_last <= 0 or t_last <= t_start or threshold <= 0:
        return None
    return t_start + (t_last - t_start) * e_last / threshold


def median_interval(values, level=0.95):
    """The median of `values` and a distribution-free confidence interval for the median of the
    distribution they were drawn from (independent draws; the sign test's interval, e.g. Hollander
    and Wolfe, "Nonparametric Statistical Methods", sec. 3.6): the k-th smallest and the k-th
    largest value, k the largest rank with P(Binomial(n, 1/2) < k) <= (1 - level) / 2, so that
    the interval misses the true median with probability at most 1 - level whatever the
    distribution. Returns (median, lo, hi, coverage): coverage = 1 - 2 P(Binomial(n, 1/2) < k), at
    least `level`; lo, hi and coverage are None when there are too few values for the level (fewer
    than 6 at 0.95). Example: 15 values at 0.95 give the 4th smallest and the 4th largest, coverage
    0.965."""
    xs = sorted(float(v) for v in values)
    n = len(xs)
    if n == 0:
        raise ValueError("median_interval: no values")
    median = xs[n // 2] if n % 2 else 0.5 * (xs[n // 2 - 1] + xs[n // 2])
    alpha = (1.0 - level) / 2.0
    k, below = 0, 0.0  # below = P(Binomial(n, 1/2) < k + 1) as k grows
    while True:
        below_next = below + math.comb(n, k) / 2.0 ** n
        if below_next > alpha:
            break
        below, k = below_next, k + 1
    if k == 0:
        return median, None, None, None
    return median, xs[k - 1], xs[n - k], 1.0 - 2.0 * below


def needed_total_spp(floor_rel, spp_total, target_floor):
    """Total spp (both halves) for a relMSE floor of target_floor, given the floor floor_rel measured
    with spp_total samples per pixel: the floor falls as 1/spp."""
    return int(math.ceil(spp_total * floor_rel / target_floor))


def interval_verdict(interval, pairs, target, at_least):
    """Issue 18's verdict on a target from the interval of a median ratio (median_interval): with
    at_least (the ratio must be >= target) "met" when the interval lies at or above the target, "not
    met" when it lies below; otherwise (<= target) "met" at or below, "not met" above; "undecided"
    when it contains the target; "no interval (N pairs)" without one (too few pairs): one run says
    little on a machine whose speed drifts."""
    if not interval:
        return "no interval (%d pair%s)" % (pairs, "" if pairs == 1 else "s")
    lo, hi = interval
    if (lo >= target) if at_least else (hi <= target):
        return "met"
    if (hi < target) if at_least else (lo > target):
        return "not met"
    return "undecided (the interval contains %gx)" % target
