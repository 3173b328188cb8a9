"""Hysteresis loops of a cyclic test: stiffness, damping and the Ramberg-Osgood model.

Definitions (those of the cyclic tests of soils and geosynthetics, JGS 0542/0543 and ASTM D8296):
  secant (equivalent) stiffness   K_eq = (S_max - S_min) / (u_max - u_min)
  dissipated energy               W_d  = the loop's area, the integral of S du around the closed
                                         loop (trapezoid rule on the loop's points, closed)
  elastic energy                  W_e  = K_eq u_a^2 / 2,  u_a = (u_max - u_min) / 2
  equivalent damping ratio        h_eq = W_d / (4 pi W_e)
Ramberg-Osgood (R-O) backbone, with alpha = 1 (S_y is then the force at which the secant
stiffness has fallen to K_0 / 2):
  u = (S / K_0) (1 + |S / S_y|^(r - 1))
and Masing's rule for the loops: from a reversal point (u_r, S_r) a branch follows the backbone
scaled by 2, u = u_r +- 2 u_bb((S - S_r) / 2). Its damping at a tip on the backbone:
  h = (2 / pi) (r - 1) / (r + 1) (1 - K_eq / K_0).
Pure numpy/scipy: no files, no figures (cyclic.py reads the runs and draws).
"""
from dataclasses import dataclass

import numpy as np

from tbagspost import rms


# ---- one loop -------------------------------------------------------------------------------
@dataclass
class Loop:
    """The measures of one closed loop (units of u and S as given)."""
    u_a: float       # half the peak-to-peak displacement
    S_a: float       # half the peak-to-peak force
    K_eq: float
    W_d: float
    W_e: float
    h_eq: float


def loop_area(u, S):
    """Integral of S du around the closed polygon of the points (trapezoid rule, the last point
    joined to the first). Positive for a loop that dissipates: S above its mean while u grows."""
    u, S = np.asarray(u, float), np.asarray(S, float)
    du = np.roll(u, -1) - u
    return float(0.5 * np.sum((S + np.roll(S, -1)) * du))


# a turn of u counts as a reversal once u has come back by this part of the loop's range (the
# film's slip, measured from particles, wiggles by less); a loop's end may be this far from its
# start, or one step of its points (rows are means over an interval, so they never quite close)
REVERSAL = 0.1
# a loop with h_eq below this runs the wrong way round (it gives energy): S's sign or the time
# order is reversed. Between it and 0: the scatter of a nearly elastic loop, reported as it is
H_WRONG_WAY = -0.02


def reversals(u, fraction=REVERSAL):
    """The number of turns of u (each counted once u has come back by `fraction` of its range)."""
    u = np.asarray(u, float)
    tol = fraction * (u.max() - u.min())
    turns, direction, extreme = 0, 0, u[0]
    for x in u[1:]:
        if direction == 0:
            if abs(x - u[0]) > tol:
                direction, extreme = (1 if x > u[0] else -1), x
        elif (x - extreme) * direction > 0:
            extreme = x                                  # further the same way
        elif (extreme - x) * direction > tol:
            turns, direction, extreme = turns + 1, -direction, x
    return turns


def measure(u, S, one_period=False):
    """Loop measures of the points (u, S) of one closed cycle. Refuses (ValueError, saying why)
    what is not one: non-finite points, no range of u, more than two turns of u (more than one
    cycle), an end far from the start (part of a cycle), a loop that runs the wrong way round.
    one_period: the points are one period of the drive (a cycle of in.cyclic), so a gap between
    end and start is drift (a film's slip creeps), not part of a cycle: the gap is not checked."""
    u, S = np.asarray(u, float), np.asarray(S, float)
    if not (np.isfinite(u).all() and np.isfinite(S).all()):
        bad = int(np.flatnonzero(~(np.isfinite(u) & np.isfinite(S)))[0])
        raise ValueError("point %d of %d is not finite (u %r, S %r)" % (bad + 1, len(u), u[bad], S[bad]))
    du, dS = u.max() - u.min(), S.max() - S.min()
    if du <= 0:
        raise ValueError("a loop needs points at different u")
    turns = reversals(u)
    if turns > 2:
        raise ValueError("u turns %d times: more than one cycle (a loop turns twice)" % turns)
    gap = abs(u[-1] - u[0])
    if not one_period and gap > max(REVERSAL * du, 1.5 * np.max(np.abs(np.diff(u)))):
        raise ValueError("the loop does not close: it ends %.3g from its start (%.0f %% of its range):"
                         " part of a cycle" % (gap, 100 * gap / du))
    K = dS / du
    u_a = du / 2
    W_d = loop_area(u, S)
    W_e = K * u_a ** 2 / 2
    h = W_d / (4 * np.pi * W_e) if W_e > 0 else float("nan")
    if h < H_WRONG_WAY:
        raise ValueError("the loop runs the wrong way round (h_eq %.3f < 0: it gives energy): S's "
                         "sign or the order of the points is reversed" % h)
    return Loop(u_a=u_a, S_a=dS / 2, K_eq=K, W_d=W_d, W_e=W_e, h_eq=h)


# ---- Ramberg-Osgood and Masing ------------------------------------------------------------------
@dataclass
class RO:
    K0: float
    S_y: float
    r: float

    def u(self, S):
        """Backbone displacement at force S."""
        S = np.asarray(S, float)
        return S / self.K0 * (1 + np.abs(S / self.S_y) ** (self.r - 1))

    def S(self, u):
        """Backbone force at displacement u (the inverse of u(S), by bisection on |S|)."""
        u = np.atleast_1d(np.asarray(u, float))
        lo, hi = np.zeros_like(u), np.abs(u) * self.K0     # u(S) >= S / K0, so |S| <= K0 |u|
        for _ in range(200):
            mid = (lo + hi) / 2
            big = self.u(mid) > np.abs(u)
            hi, lo = np.where(big, mid, hi), np.where(big, lo, mid)
        return np.sign(u) * (lo + hi) / 2

    def secant_ratio(self, S_a):
        """K_eq / K0 at a tip of force S_a on the backbone."""
        return 1.0 / (1 + np.abs(np.asarray(S_a, float) / self.S_y) ** (self.r - 1))

    def damping(self, S_a):
        """h of the Masing loop through the tips +-S_a."""
        return 2 / np.pi * (self.r - 1) / (self.r + 1) * (1 - self.secant_ratio(S_a))

    def branch_u(self, S, u_r, S_r):
        """u on the Masing branch from the reversal (u_r, S_r) at force S (either direction)."""
        return u_r + 2 * self.u((np.asarray(S, float) - S_r) / 2)

    def loop(self, S_a, n=200):
        """A closed Masing loop through (u_a, S_a) and (-u_a, -S_a): u, S of n points, descending
        from the top tip then ascending."""
        u_a = float(self.u(S_a))
        s_down = np.linspace(S_a, -S_a, n // 2, endpoint=False)
        s_up = np.linspace(-S_a, S_a, n - n // 2, endpoint=False)
        return (np.concatenate([self.branch_u(s_down, u_a, S_a), self.branch_u(s_up, -u_a, -S_a)]),
                np.concatenate([s_down, s_up]))


def branches(u, S):
    """Splits the points of one cycle into Masing branches: for each point the reversal it
    comes from, the top tip (u at its max) for a descending point, the bottom tip for an
    ascending one. Returns (u_r, S_r) arrays."""
    u, S = np.asarray(u, float), np.asarray(S, float)
    top, bot = int(np.argmax(u)), int(np.argmin(u))
    # direction of each point: the sign of du across it (one-sided at the ends)
    g = np.gradient(u)
    down = g < 0
    u_r = np.where(down, u[top], u[bot])
    S_r = np.where(down, S[top], S[bot])
    return u_r, S_r


@dataclass
class Fit:
    model: RO
    sigma: RO                # 1-standard-deviation uncertainty of each parameter
    rms_backbone: float      # rms of (u_model - u) / u_a at the tips
    rms_loops: float         # rms of (u_model - u) / u_a over the loops' points
    n_points: int


def fit(loops, tips=None, guess=None):
    """Least-squares R-O fit to loops (a list of (u, S) arrays, one closed cycle each) and their
    tips (default: each loop's (u_a, S_a)). The residuals are in u, relative to each loop's u_a so
    that every amplitude weighs alike: at the tips u_bb(S_a) - u_a, along the loops the Masing
    branch's u at the point's S minus its u, divided by sqrt(points of the loop) so that a whole
    loop weighs as much as one tip (the backbone and the loops count alike, whatever the rows per
    cycle). Parameters fitted in logs (K0, S_y > 0, r > 1). The rms errors reported are plain
    (unweighted) means over the tips and over the loops' points."""
    from scipy.optimize import least_squares

    loops = [(np.asarray(u, float), np.asarray(S, float)) for u, S in loops]
    measures = [measure(u, S) for u, S in loops]
    if tips is None:
        tips = [(m.u_a, m.S_a) for m in measures]
    tips = np.asarray(tips, float)
    ua = tips[:, 0]
    prepared = []
    for (u, S), m in zip(loops, measures):
        u_r, S_r = branches(u, S)
        prepared.append((u, S, u_r, S_r, m.u_a))

    def params(x):
        return RO(K0=np.exp(x[0]), S_y=np.exp(x[1]), r=1 + np.exp(x[2]))

    def residuals(x):
        ro = params(x)
        res = [(ro.u(tips[:, 1]) - ua) / ua]
        for u, S, u_r, S_r, a in prepared:
            res.append((ro.branch_u(S, u_r, S_r) - u) / (a * np.sqrt(len(u))))
        return np.concatenate(res)

    if guess is None:
        k_small = tips[np.argmin(ua), 1] / ua.min()
        guess = RO(K0=1.5 * k_small, S_y=np.median(tips[:, 1]), r=2.0)
    x0 = [np.log(guess.K0), np.log(guess.S_y), np.log(guess.r - 1)]
    sol = least_squares(residuals, x0, x_scale="jac", method="lm", max_nfev=20000)
    ro = params(sol.x)
    m, n = len(sol.fun), len(sol.x)
    # covariance of the log parameters from the Jacobian, scaled by the residual variance
    s2 = float(np.sum(sol.fun ** 2)) / max(m - n, 1)
    try:
        cov = np.linalg.inv(sol.jac.T @ sol.jac) * s2
        sd = np.sqrt(np.clip(np.diag(cov), 0, None))
    except np.linalg.LinAlgError:
        sd = np.full(3, np.nan)
    sigma = RO(K0=ro.K0 * sd[0], S_y=ro.S_y * sd[1], r=(ro.r - 1) * sd[2])
    nb = len(tips)
    loop_err = np.concatenate([(ro.branch_u(S, u_r, S_r) - u) / a for u, S, u_r, S_r, a in prepared])
    return Fit(model=ro, sigma=sigma, rms_backbone=rms(sol.fun[:nb]),
               rms_loops=rms(loop_err) if len(loop_err) else float("nan"),
               n_points=m)
