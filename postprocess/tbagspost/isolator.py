"""Isolator models of a bag's (or a stack's) shear force S against its displacement u, the
models a structural analysis uses for isolator elements; each turns a displacement history into
the force along it, and is fitted to the loops of a cyclic run.

  MasingRO   Ramberg-Osgood backbone u = (S/K_0)(1 + |S/S_y|^(r-1)) and the extended Masing
             rules (Kramer 1996, Geotechnical Earthquake Engineering, sec. 6.4.3): a branch from a
             reversal (u_r, S_r) is S = S_r + 2 S_bb((u - u_r)/2); past the largest |u| so far it
             follows the backbone; a branch that reaches the reversal it started from continues the
             curve that reversal interrupted (inner loops close).
  MasingROF  the same backbone with the damping reduction of Phillips and Hashash (2009, Soil Dyn.
             Earthq. Eng. 29:1143): a branch is S = S_r + F(u_m)[2 S_bb(du/2) - K_m du] + K_m du,
             du = u - u_r, u_m the largest |u| so far, K_m = S_bb(u_m)/u_m its secant stiffness and
             F(u_m) = p1 - p2 (1 - K_m/K_0)^p3: the loop of amplitude u_m closes at its tips and
             dissipates F(u_m) times Masing's energy (the K_m du part is a line, no area).
  Bilinear   the bilinear isolator of the AASHTO Guide Specifications for Seismic Isolation Design
             (2014) and ASCE 7-22 ch. 17: elastic stiffness K_u, characteristic strength Q_d (the
             force at u = 0 on a loop), post-yield stiffness K_d; yield displacement
             D_y = Q_d/(K_u - K_d) (kinematic hardening: S within K_d u +- Q_d).
  BoucWen    S = a K u + (1 - a) K D_y z with dz/du = (1 - |z|^n (b + (1 - b) sgn(du z)))/D_y
             (Wen 1976, J. Eng. Mech. Div. 102:249, normalised so that |z| <= 1): initial stiffness
             K, post-yield ratio a, yield displacement D_y, sharpness n, shape b.
  Slider     a friction slider (force limit mu N) in series with a bag model: the stack of bags on
             films (u = bags' u + slip; the same S through both).

Fits: MasingRO as hysteresis.fit (tips and loops, residuals in u); MasingROF's backbone is that
fit and F(u_m) is fitted to the measured damping (Phillips and Hashash's two-step procedure:
the backbone to the stiffness reduction, F to the damping); Bilinear and BoucWen by least squares
on S along the loops. A loop set is `Lanes`: per amplitude, the cycle before the last (to reach the
steady loop from rest) and the last cycle, which alone is compared. Pure numpy/scipy.
"""
from dataclasses import dataclass, field

import numpy as np

from tbagspost import hysteresis, rms


# ---- the loops a model is fitted to ---------------------------------------------------------
@dataclass
class Lanes:
    """Per amplitude (one lane each): u and S of a warm-up cycle followed by the last cycle;
    `start` is where the last cycle begins in each lane."""
    u: list
    S: list
    start: list

    def last(self, k, values):
        """The last cycle's part of lane k's values (an array along lane k)."""
        return np.asarray(values)[self.start[k]:]

    def measures(self, S=None):
        """hysteresis.Loop of each lane's last cycle (of S if given, else the data's)."""
        S = self.S if S is None else S
        return [hysteresis.measure(self.last(k, self.u[k]), self.last(k, S[k])) for k in range(len(self.u))]


def lanes_of(cycles):
    """Lanes from a run's complete cycles [(amp, cycle, rows), ...] (cyclic.CyclicRun.cycles):
    per amplitude its last cycle, after the cycle before it (or alone if it has one cycle)."""
    by_amp = {}
    for amp, _, rows in cycles:
        by_amp.setdefault(amp, []).append(rows)
    u, S, start = [], [], []
    for amp in sorted(by_amp):
        rows = by_amp[amp][-2:]
        u.append(np.concatenate([r["u_mm"] for r in rows]))
        S.append(np.concatenate([r["S_N"] for r in rows]))
        start.append(len(rows[0]) if len(rows) == 2 else 0)
    return Lanes(u=u, S=S, start=start)


# ---- models: each steps through a displacement history ---------------------------------------
# A model's stepper() starts at rest (u = 0, S = 0); stepper.step(u) moves it to u and returns S;
# stepper.copy() is an independent copy (the slider tries steps). simulate(u) runs a whole path.
class Model:
    def simulate(self, u):
        st = self.stepper()
        return np.array([st.step(x) for x in np.asarray(u, float)])


class MasingStepper:
    """The extended Masing rules: on the backbone while |u| grows past its largest value so far;
    from a reversal (u_r, S_r) along branch(u - u_r, u_m); a branch that reaches the point it aims
    at (the reversal before its own, or the mirror of the backbone's tip) ends there, and the curve
    it interrupted goes on."""

    def __init__(self, backbone, branch):
        self.backbone, self.branch = backbone, branch
        self.stack, self.umax, self.direction, self.u, self.S = [], 0.0, 0.0, 0.0, 0.0

    def copy(self):
        c = MasingStepper(self.backbone, self.branch)
        c.stack, c.umax, c.direction, c.u, c.S = list(self.stack), self.umax, self.direction, self.u, self.S
        return c

    def step(self, u):
        du = u - self.u
        if du == 0.0:
            return self.S
        d = 1.0 if du > 0 else -1.0
        if self.direction != 0.0 and d != self.direction:
            self.stack.append((self.u, self.S))
        self.direction = d
        while self.stack:
            aim = self.stack[-2][0] if len(self.stack) >= 2 else d * self.umax
            if (u - aim) * d <= 0.0:
                break
            del self.stack[-2:]
        if self.stack:
            u_r, S_r = self.stack[-1]
            self.S = S_r + self.branch(u - u_r, self.umax)
        else:
            self.umax = max(self.umax, abs(u))
            self.S = self.backbone(u)
        self.u = u
        return self.S


@dataclass
class MasingRO(Model):
    """Ramberg-Osgood backbone with the extended Masing rules (hysteresis.RO's parameters)."""
    K0: float
    S_y: float
    r: float
    name = "R-O, Masing"
    reach = 50.0      # the backbone is tabulated to this |u| (grown to twice a path's largest |u|)

    @property
    def ro(self):
        return hysteresis.RO(self.K0, self.S_y, self.r)

    def backbone_fn(self, reach):
        """S_bb(v), interpolated in a table of the inverse of u(S) up to |v| = reach."""
        x = np.linspace(0.0, reach, 4001)
        s = self.ro.S(x)
        return lambda v: float(np.copysign(np.interp(abs(v), x, s), v))

    def branch_fn(self, sbb):
        return lambda du, um: 2.0 * sbb(du / 2.0)

    def stepper(self, reach=None):
        sbb = self.backbone_fn(reach or self.reach)
        return MasingStepper(sbb, self.branch_fn(sbb))

    def simulate(self, u):
        u = np.asarray(u, float)
        st = self.stepper(1.01 * max(np.abs(u).max(), 1e-9))
        return np.array([st.step(x) for x in u])

    def params(self):
        return dict(K0=self.K0, S_y=self.S_y, r=self.r)


@dataclass
class MasingROF(MasingRO):
    """R-O backbone, Masing branches reduced by Phillips and Hashash's F(u_m)."""
    p1: float = 1.0
    p2: float = 0.0
    p3: float = 1.0
    name = "R-O, Phillips-Hashash"

    def F(self, um):
        ratio = self.ro.secant_ratio(self.ro.S(um))
        return self.p1 - self.p2 * (1.0 - ratio) ** self.p3

    def damping(self, um):
        """h of the steady loop of amplitude um: F(um) times Masing's."""
        return self.F(um) * self.ro.damping(self.ro.S(um))

    def branch_fn(self, sbb):
        cache = {}

        def branch(du, um):
            if um <= 0.0:
                return 2.0 * sbb(du / 2.0)
            if um not in cache:
                cache.clear()
                cache[um] = (float(self.F(um)[0]), sbb(um) / um)
            f, km = cache[um]
            return f * (2.0 * sbb(du / 2.0) - km * du) + km * du
        return branch

    def params(self):
        return dict(K0=self.K0, S_y=self.S_y, r=self.r, p1=self.p1, p2=self.p2, p3=self.p3)


class _State:
    """A stepper whose whole state is a few numbers (copy: a shallow copy)."""

    def copy(self):
        c = object.__new__(type(self))
        c.__dict__.update(self.__dict__)
        return c


@dataclass
class Bilinear(Model):
    """Kinematic-hardening bilinear isolator."""
    K_u: float
    Q_d: float
    K_d: float
    name = "bilinear"

    @property
    def D_y(self):
        return self.Q_d / (self.K_u - self.K_d)

    def stepper(self):
        m = self

        class Step(_State):
            u = S = 0.0

            def step(self, u):
                lo = m.K_d * u - m.Q_d
                self.S = min(max(self.S + m.K_u * (u - self.u), lo), lo + 2.0 * m.Q_d)
                self.u = u
                return self.S
        return Step()

    def params(self):
        return dict(K_u=self.K_u, Q_d=self.Q_d, K_d=self.K_d, D_y=self.D_y)


@dataclass
class BoucWen(Model):
    """Bouc-Wen hysteresis, integrated over each step of u by the midpoint rule on sub-steps of at
    most D_y/50."""
    K: float
    a: float
    D_y: float
    n: float
    b: float
    name = "Bouc-Wen"

    def dz(self, z, du):
        s = 1.0 if du * z > 0 else (-1.0 if du * z < 0 else 0.0)
        return du / self.D_y * (1.0 - abs(z) ** self.n * (self.b + (1.0 - self.b) * s))

    def stepper(self):
        m = self

        class Step(_State):
            u = z = 0.0

            def step(self, u):
                du = u - self.u
                k = max(1, int(np.ceil(abs(du) / (m.D_y / 50.0))))
                h, z = du / k, self.z
                for _ in range(k):
                    z = min(max(z + m.dz(z + 0.5 * m.dz(z, h), h), -1.0), 1.0)
                self.u, self.z = u, z
                return m.a * m.K * u + (1.0 - m.a) * m.K * m.D_y * z
        return Step()

    def params(self):
        return dict(K=self.K, a=self.a, D_y=self.D_y, n=self.n, b=self.b)


@dataclass
class Slider(Model):
    """A friction slider of strength mu_N (N) and elastic stiffness k_slip (N/mm, before it slips:
    an elastic-perfectly-plastic interface; inf: rigid-plastic) in series with `bags` equal bags of
    model `bag`: the bags take u_b, each u_b/bags, the interface S/k_slip while |S| < mu_N; past
    mu_N the rest of u slips."""
    bag: object
    mu_N: float
    bags: int = 1
    k_slip: float = float("inf")
    name = "slider + bags"

    def stepper(self):
        m = self

        def split(bag, target):
            """The bags' share ub of `target` (= ub + S(ub)/k_slip), S(ub) from a copy of bag."""
            if not np.isfinite(m.k_slip):
                return target
            lo, hi = min(0.0, target) - abs(target), max(0.0, target) + abs(target)
            for _ in range(60):
                mid = 0.5 * (lo + hi)
                if mid + bag.copy().step(mid / m.bags) / m.k_slip < target:
                    lo = mid
                else:
                    hi = mid
            return 0.5 * (lo + hi)

        class Step:
            def __init__(self):
                self.bag, self.ub, self.slip = m.bag.stepper(), 0.0, 0.0

            def step(self, u):
                ub = split(self.bag, u - self.slip)
                trial = self.bag.copy()
                s = trial.step(ub / m.bags)
                if abs(s) <= m.mu_N:
                    self.bag, self.ub = trial, ub
                    return s
                lo, hi = self.ub, ub                  # the bags' share at which |S| reaches mu_N
                for _ in range(40):
                    mid = 0.5 * (lo + hi)
                    if abs(self.bag.copy().step(mid / m.bags)) < m.mu_N:
                        lo = mid
                    else:
                        hi = mid
                self.bag.step(lo / m.bags)
                S = float(np.copysign(m.mu_N, s))
                self.ub, self.slip = lo, u - lo - S / m.k_slip
                return S
        return Step()

    def params(self):
        return dict(mu_N=self.mu_N, k_slip=self.k_slip, bags=self.bags, **self.bag.params())


# ---- fits ------------------------------------------------------------------------------------
@dataclass
class ModelFit:
    """A fitted model, its parameters' standard deviations, and its errors on the last cycles:
    rms of S along the loops over each loop's S_a, and per lane K_eq (relative) and h_eq (abs)."""
    model: object
    sd: dict
    rms_S: float
    K_eq: list = field(default_factory=list)       # (data, model) per lane
    h_eq: list = field(default_factory=list)
    u_a: list = field(default_factory=list)        # the data's per lane
    label: str = ""                                # the model's name unless given

    @property
    def name(self):
        return self.label or self.model.name

    @property
    def worst_K(self):
        return max(abs(m / d - 1.0) for d, m in self.K_eq)

    @property
    def worst_h(self):
        return max(abs(m - d) for d, m in self.h_eq)


def evaluate(model, lanes, sd=None, label=""):
    """A model's errors on the lanes' last cycles (ModelFit)."""
    sims = [model.simulate(u) for u in lanes.u]
    data, fitted = lanes.measures(), lanes.measures(sims)
    err = np.concatenate([(lanes.last(k, sims[k]) - lanes.last(k, lanes.S[k])) / data[k].S_a
                          for k in range(len(sims))])
    return ModelFit(model=model, sd=sd or {}, rms_S=rms(err),
                    K_eq=[(d.K_eq, f.K_eq) for d, f in zip(data, fitted)],
                    h_eq=[(d.h_eq, f.h_eq) for d, f in zip(data, fitted)], u_a=[d.u_a for d in data],
                    label=label)


def _least_squares(make, x0, lanes, bounds=(-np.inf, np.inf)):
    """Least squares on S along the lanes' last cycles (each lane over its S_a and the root of its
    points, so that every amplitude weighs alike); x are the model's parameters as make(x) takes
    them. Returns the model and the standard deviations of its parameters (from the Jacobian)."""
    from scipy.optimize import least_squares

    scale = [hysteresis.measure(lanes.last(k, lanes.u[k]), lanes.last(k, lanes.S[k])).S_a
             * np.sqrt(len(lanes.last(k, lanes.u[k]))) for k in range(len(lanes.u))]

    def residuals(x):
        m = make(x)
        return np.concatenate([(lanes.last(k, m.simulate(u)) - lanes.last(k, lanes.S[k])) / scale[k]
                               for k, u in enumerate(lanes.u)])

    sol = least_squares(residuals, x0, x_scale="jac", bounds=bounds, max_nfev=400)
    return make(sol.x), sol.x, covariance_sd(sol)


def covariance_sd(sol):
    """Standard deviations of a least-squares solution's parameters: the Jacobian's covariance
    scaled by the residuals' variance."""
    s2 = float(np.sum(sol.fun ** 2)) / max(len(sol.fun) - len(sol.x), 1)
    try:
        return np.sqrt(np.clip(np.diag(np.linalg.inv(sol.jac.T @ sol.jac) * s2), 0, None))
    except np.linalg.LinAlgError:
        return np.full(len(sol.x), np.nan)


def fit_masing(lanes):
    """R-O + Masing, fitted as hysteresis.fit does (tips and loops of the last cycles)."""
    loops = [(lanes.last(k, lanes.u[k]), lanes.last(k, lanes.S[k])) for k in range(len(lanes.u))]
    f = hysteresis.fit(loops)
    m = MasingRO(f.model.K0, f.model.S_y, f.model.r)
    return evaluate(m, lanes, dict(K0=f.sigma.K0, S_y=f.sigma.S_y, r=f.sigma.r))


def fit_reduced(lanes, masing):
    """Phillips and Hashash's two steps: the R-O backbone through the last cycles' tips (u_bb(S_a)
    = u_a, the stiffness reduction curve; `masing`, a MasingRO, is the first guess), then p1, p2,
    p3 by least squares on their h_eq (F = h_eq / h_Masing at each amplitude), with p1 and p2 in
    [0, 1] (F reduces Masing's damping; it cannot add the small-amplitude damping Masing lacks)."""
    from scipy.optimize import least_squares

    data = lanes.measures()
    ua = np.array([d.u_a for d in data])
    Sa = np.array([d.S_a for d in data])
    h = np.array([d.h_eq for d in data])

    def ro(x):
        return hysteresis.RO(K0=np.exp(x[0]), S_y=np.exp(x[1]), r=1.0 + np.exp(x[2]))

    bb = least_squares(lambda x: ro(x).u(Sa) / ua - 1.0,
                       [np.log(masing.K0), np.log(masing.S_y), np.log(masing.r - 1.0)], method="lm")
    b, sd_b = ro(bb.x), covariance_sd(bb)

    def make(x):
        return MasingROF(b.K0, b.S_y, b.r, p1=x[0], p2=x[1], p3=x[2])

    sol = least_squares(lambda x: make(x).damping(ua) - h, [1.0, 0.5, 1.0],
                        bounds=([0.0, 0.0, 0.05], [1.0, 1.0, 20.0]))
    sd = dict(K0=b.K0 * sd_b[0], S_y=b.S_y * sd_b[1], r=(b.r - 1.0) * sd_b[2])
    sd.update(zip(("p1", "p2", "p3"), covariance_sd(sol)))
    return evaluate(make(sol.x), lanes, sd)


def bilinear_guess(lanes):
    """K_u from the smallest loop's K_eq; Q_d and K_d from the largest loop (its force at u = 0
    and its tip: K_d = (S_a - Q_d)/u_a)."""
    data = lanes.measures()
    small, big = int(np.argmin([d.u_a for d in data])), int(np.argmax([d.u_a for d in data]))
    q = zero_crossing_force(lanes.last(big, lanes.u[big]), lanes.last(big, lanes.S[big]))
    K_u = data[small].K_eq * 1.2
    K_d = max((data[big].S_a - q) / data[big].u_a, 1e-3 * K_u)
    return Bilinear(K_u=K_u, Q_d=q, K_d=min(K_d, 0.5 * K_u))


def fit_bilinear(lanes):
    g = bilinear_guess(lanes)
    model, x, sd = _least_squares(lambda x: Bilinear(*np.exp(x)), np.log([g.K_u, g.Q_d, g.K_d]), lanes)
    return evaluate(model, lanes, dict(K_u=model.K_u * sd[0], Q_d=model.Q_d * sd[1], K_d=model.K_d * sd[2]))


def fit_bouc_wen(lanes, start=None):
    """Bouc-Wen from the bilinear fit's K_u, K_d/K_u and D_y, n = 1, b = 0.5."""
    g = start if start is not None else fit_bilinear(lanes).model
    x0 = [np.log(g.K_u), np.log(g.K_d / g.K_u), np.log(g.D_y), np.log(1.0), 0.5]

    def make(x):
        return BoucWen(K=np.exp(x[0]), a=min(np.exp(x[1]), 0.999), D_y=np.exp(x[2]),
                       n=np.exp(x[3]), b=x[4])

    lo = [-np.inf, np.log(1e-4), -np.inf, np.log(0.3), -1.0]
    hi = [np.inf, np.log(0.999), np.inf, np.log(10.0), 1.0]
    model, x, sd = _least_squares(make, x0, lanes, bounds=(lo, hi))
    return evaluate(model, lanes, dict(K=model.K * sd[0], a=model.a * sd[1], D_y=model.D_y * sd[2],
                                       n=model.n * sd[3], b=sd[4]))


def zero_crossing_force(u, S):
    """Half the range of S where the closed loop crosses u = 0 (the mean |S| at the crossings,
    linearly interpolated): Q_d of a measured loop."""
    u, S = np.asarray(u, float), np.asarray(S, float)
    u2, S2 = np.append(u, u[0]), np.append(S, S[0])
    s = []
    for k in range(len(u)):
        if u2[k] == 0.0:
            s.append(S2[k])
        elif u2[k] * u2[k + 1] < 0.0:
            t = u2[k] / (u2[k] - u2[k + 1])
            s.append(S2[k] + t * (S2[k + 1] - S2[k]))
    if len(s) < 2:
        raise ValueError("the loop does not cross u = 0 twice")
    return float((max(s) - min(s)) / 2.0)


def fit_all(lanes):
    """The four single-bag models fitted to the lanes: [ModelFit]; Phillips-Hashash only with 3
    amplitudes or more (its backbone's 3 parameters are fitted to the tips, its reduction's 3 to
    the h_eq: fewer amplitudes leave it undetermined)."""
    masing = fit_masing(lanes)
    bil = fit_bilinear(lanes)
    reduced = [fit_reduced(lanes, masing.model)] if len(lanes.u) >= 3 else []
    return [masing] + reduced + [bil, fit_bouc_wen(lanes, bil.model)]


def recommend(fits, K_tol=0.10, h_tol=0.03):
    """The model to use: among those within K_tol (relative) and h_tol (absolute) at every
    amplitude, the one with the smallest rms S error; if none is, the smallest rms. Returns the
    ModelFit and a sentence saying why."""
    ok = [f for f in fits if f.worst_K <= K_tol and f.worst_h <= h_tol]
    pool = ok or fits
    best = min(pool, key=lambda f: f.rms_S)
    why = ("%s: K_eq within %.0f %% and h_eq within %.3f at every amplitude, and the smallest rms "
           "error of S along the loops (%.1f %%)" % (best.name, 100 * best.worst_K, best.worst_h,
                                                     100 * best.rms_S) if ok else
           "%s: the smallest rms error of S (%.1f %%); no model is within %.0f %% on K_eq and %.2f on "
           "h_eq at every amplitude (worst here: K_eq %.0f %%, h_eq %.3f)" % (
               best.name, 100 * best.rms_S, 100 * K_tol, h_tol, 100 * best.worst_K, best.worst_h))
    return best, why
