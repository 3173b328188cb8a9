"""Isolator properties in a structural designer's terms, from the loops of cyclic runs, with
their bounds as property modification factors.

Per loop (one cycle, displacements Delta+ = max u, Delta- = min u, forces F+ and F- at them):
  ASCE 7-22 ch. 17 (prototype tests) and the AASHTO Guide Specifications for Seismic Isolation
  Design (2014):
    effective stiffness  k_eff = (|F+| + |F-|) / (|Delta+| + |Delta-|)
    effective damping    beta_eff = (2/pi) E_loop / (k_eff (|Delta+| + |Delta-|)^2)
  with E_loop the loop's area. For a loop symmetric about the origin whose largest forces are at
  its largest displacements these are K_eq and h_eq of hysteresis.py (K_eq uses S_max - S_min,
  k_eff the forces at the displacement peaks; the report gives their largest difference).
  The equivalent bilinear loop of the same D = (|Delta+| + |Delta-|)/2, k_eff and E_loop (AASHTO):
    Q_d  characteristic strength: the force where the loop crosses u = 0 (half the range)
    K_d  post-yield stiffness: k_eff - Q_d / D
    D_y  yield displacement: D - E_loop / (4 Q_d)   (E_loop = 4 Q_d (D - D_y))
    K_u  elastic stiffness: K_d + Q_d / D_y
Property modification factors (ASCE 7-22 sec. 17.2.8.4), each a (lambda_min, lambda_max) pair
of a property's extreme over its nominal value, per amplitude and over all amplitudes:
  cycles     first cycle against the mean of the cycles (as prototype tests compare them):
             P_1 / mean(P_i); every cycle's P_i / mean as the range
  rate       the same load at half the speed: P_slow / P_fast (last cycles)
  fills      several fills (realizations) of the same load: min and max of P / mean
  combined   lambda_max = lambda_cycles,max lambda_rate,max lambda_fills,max and the same for the
             minima (the standard's product; aging and environment, lambda_ae, are not modelled: 1)
"""
import csv
from dataclasses import asdict, dataclass

import numpy as np

from tbagspost import hysteresis, isolator

PROPS = ("k_eff", "beta_eff", "Q_d", "K_d", "D_y")


@dataclass
class Properties:
    D: float
    k_eff: float
    beta_eff: float
    E_loop: float
    Q_d: float
    K_d: float
    D_y: float
    K_u: float
    K_eq: float
    h_eq: float


def properties(u, S):
    """The designer's properties of one closed loop (units of u and S as given)."""
    u, S = np.asarray(u, float), np.asarray(S, float)
    if not (np.isfinite(u).all() and np.isfinite(S).all()):
        raise ValueError("a loop with a non-finite u or S")
    top, bot = int(np.argmax(u)), int(np.argmin(u))
    span = u[top] - u[bot]
    k_eff = (abs(S[top]) + abs(S[bot])) / span if u[top] > 0 > u[bot] else (S[top] - S[bot]) / span
    E = hysteresis.loop_area(u, S)
    D = span / 2
    beta = 2 / np.pi * E / (k_eff * span ** 2)
    Q = isolator.zero_crossing_force(u, S)
    K_d = k_eff - Q / D
    D_y = D - E / (4 * Q) if Q > 0 else float("nan")
    K_u = K_d + Q / D_y if D_y > 0 else float("nan")
    m = hysteresis.measure(u, S)
    return Properties(D=D, k_eff=k_eff, beta_eff=beta, E_loop=E, Q_d=Q, K_d=K_d, D_y=D_y, K_u=K_u,
                      K_eq=m.K_eq, h_eq=m.h_eq)


def run_table(run):
    """{(amp, cycle): Properties} of a cyclic.CyclicRun's complete cycles (u in mm, S in N)."""
    return {(amp, cyc): properties(rows["u_mm"], rows["S_N"]) for amp, cyc, rows in run.cycles()}


def _ratio_range(values, nominal):
    values = np.asarray(values, float) / nominal
    return float(values.min()), float(values.max())


def negligible(p, props):
    """A property too small to scale: K_d below 5 % of k_eff (a slider's loop has no post-yield
    stiffness; ratios of values near zero say nothing)."""
    return p == "K_d" and abs(props.K_d) < 0.05 * abs(props.k_eff)


def lambdas(table, slow=None, fills=()):
    """Property modification factors per amplitude and property: {amp: {prop: {source: (min,
    max)}}} with sources 'cycles', 'rate' (slow: the half-speed run's table), 'fills' (tables of
    the other fills of the same load) and 'combined'. A source without data, and a negligible
    property (negligible()), are left out."""
    out = {}
    for amp in sorted({a for a, _ in table}):
        cycles = sorted(c for a, c in table if a == amp)
        last = table[(amp, cycles[-1])]
        per = {}
        for p in PROPS:
            if any(negligible(p, table[(amp, c)]) for c in cycles):
                continue
            vals = [getattr(table[(amp, c)], p) for c in cycles]
            mean = float(np.mean(vals))
            src = {}
            if len(vals) > 1 and mean != 0:
                first = vals[0] / mean
                lo, hi = _ratio_range(vals, mean)
                src["cycles"] = (min(first, lo), max(first, hi))
            if slow is not None:
                sc = sorted(c for a, c in slow if a == amp)
                if sc and getattr(last, p) != 0:
                    r = getattr(slow[(amp, sc[-1])], p) / getattr(last, p)
                    src["rate"] = (min(r, 1.0), max(r, 1.0))
            others = [t[(amp, max(c for a, c in t if a == amp))] for t in fills
                      if any(a == amp for a, _ in t)]
            if others:
                vals = [getattr(last, p)] + [getattr(o, p) for o in others]
                src["fills"] = _ratio_range(vals, float(np.mean(vals)))
            if src:
                src["combined"] = (float(np.prod([v[0] for v in src.values()])),
                                   float(np.prod([v[1] for v in src.values()])))
            per[p] = src
        out[amp] = per
    return out


def envelope(lam):
    """Over all amplitudes: {prop: {source: (min, max)}} (the smallest minimum, largest maximum)."""
    env = {}
    for per in lam.values():
        for p, src in per.items():
            for s, (lo, hi) in src.items():
                a, b = env.setdefault(p, {}).get(s, (np.inf, -np.inf))
                env[p][s] = (min(a, lo), max(b, hi))
    return env


def write_csv(path, rows):
    """rows: dicts; the columns are every key in order of first appearance (blank where a row
    lacks one)."""
    keys = list(dict.fromkeys(k for r in rows for k in r))
    with open(path, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=keys, restval="")
        w.writeheader()
        for r in rows:
            w.writerow({k: ("%.6g" % v if isinstance(v, float) else v) for k, v in r.items()})


def property_rows(name, fv, table, lam, fabric="solid"):
    """CSV rows: per amplitude's last cycle, its properties and each lambda."""
    rows = []
    for amp in sorted(lam):
        last = table[(amp, max(c for a, c in table if a == amp))]
        row = dict(run=name, Fv_N=fv, fabric=fabric, amp=amp)
        row.update({k: float(v) for k, v in asdict(last).items()})
        for p, src in lam[amp].items():
            for s, (lo, hi) in src.items():
                row["%s_lambda_%s_min" % (p, s)] = lo
                row["%s_lambda_%s_max" % (p, s)] = hi
        rows.append(row)
    return rows
