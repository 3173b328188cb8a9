"""The samples (one per confining stress, void ratio reached by the preparation friction) and the
triaxial runs of a parameter set, each cached."""
import math
import threading
from pathlib import Path

from .common import PAPER, PREP_MU_MAX, PREP_MU_START, PREP_SLOPE, PREP_TRIES, fail, fmt, twisting_coeffs
from .runs import Cache, RESTART_FORMAT, deck_hash, run_deck, summary


class Calibration:
    def __init__(self, a, share=None):
        """share: another Calibration in the same work directory whose caches and locks this one
        uses (variants of the options, e.g. another seed, run side by side)."""
        self.a = a
        self.work = Path(a.workdir)
        if share is None:
            self.prep_cache = Cache(self.work / "prep.json")
            self.eval_cache = Cache(self.work / "evaluations.json")
            self.prep_locks = {}
            self.lock = threading.Lock()
        else:
            self.prep_cache, self.eval_cache = share.prep_cache, share.eval_cache
            self.prep_locks, self.lock = share.prep_locks, share.lock

    def dt(self, E):
        """--dt for grains up to the paper's E; for stiffer ones scaled by sqrt(E_paper / E), the
        same fraction of the Rayleigh step (which falls as 1 / sqrt(E))."""
        return self.a.dt * math.sqrt(min(1.0, PAPER["E"] / E))

    def decks(self):
        """(preparation deck, shear deck, the files both include) of the --cell chosen."""
        if self.a.cell == "periodic":
            return "in.triax_prep_periodic", "in.triax_periodic", ("pcell.inc", "grains.inc", "sample.inc", "gains.inc")
        return "in.triax_prep", "in.triax", ("cell.inc", "grains.inc", "sample.inc", "gains.inc")

    def deck_key(self, stage):
        """Hash of the preparation (stage 0) or shear (stage 1) deck with its includes."""
        decks = self.decks()
        return deck_hash(decks[stage], *decks[2])

    def cell_vars(self, E):
        a = self.a
        return {"W": fmt(a.width), "H": fmt(a.height), "dt": fmt(self.dt(E))}

    # ---- samples ------------------------------------------------------------------------
    def seeds(self):
        """The samples per pressure: --seeds of them from --seed on."""
        return list(range(self.a.seed, self.a.seed + self.a.seeds))

    def prep_key(self, p, E, seed=None):
        a = self.a
        return "p%s_E%s_e%s_W%s_H%s_seed%d_dt%s_deck%s_r%d" % (
            fmt(p), fmt(E), fmt(a.void_ratio), fmt(a.width), fmt(a.height),
            a.seed if seed is None else seed, fmt(self.dt(E)),
            self.deck_key(0), RESTART_FORMAT)

    def sample(self, p, E, seed=None):
        """Restart file of the sample at sigma3 = p MPa (void ratio within tolerance)."""
        seed = self.a.seed if seed is None else seed
        key = self.prep_key(p, E, seed)
        with self.lock:
            lk = self.prep_locks.setdefault(key, threading.Lock())
        with lk:
            hit = self.prep_cache.get(key)
            if hit and Path(hit["restart"]).is_file():
                return hit
            return self._prepare(p, E, key, seed)

    def _prepare(self, p, E, key, seed):
        a = self.a
        target, tol = a.void_ratio, a.e_tol
        tries = []
        mu = PREP_MU_START
        for k in range(PREP_TRIES):
            d = self.work / "prep" / key / ("mu%s" % fmt(mu))
            out, secs = run_deck(self.decks()[0], d, dict(
                self.cell_vars(E), sigma3=fmt(p * 1e6), E=fmt(E), mu_prep=fmt(mu), e0=fmt(target),
                seed=seed, out="prep.restart"))
            e = summary(d, "prep")["void_ratio"]
            tries.append((mu, e))
            print("fit.py: sample %g MPa (seed %d): mu_prep %.4f -> void ratio %.4f (%.0f s)" % (p, seed, mu, e, secs),
                  flush=True)
            if abs(e - target) <= tol:
                rec = {"restart": str(d / "prep.restart"), "mu_prep": mu, "e": e, "tries": tries,
                       "seconds": secs}
                self.prep_cache.put(key, rec)
                return rec
            # next guess: between the closest tries on either side of the target when there are
            # such (e rises with mu_prep, but with the packing's noise: a secant through two tries
            # on one side can point the wrong way); else a secant through the two closest tries,
            # else the default slope
            below = [t for t in tries if t[1] < target]
            above = [t for t in tries if t[1] > target]
            lo = max(below, key=lambda t: t[1]) if below else None
            hi = min(above, key=lambda t: t[1]) if above else None
            if lo and hi and lo[0] < hi[0]:
                slope, base_mu, base_e = (hi[1] - lo[1]) / (hi[0] - lo[0]), lo[0], lo[1]
            else:
                # every try on one side: step on from the try furthest the way to go (the lowest
                # mu_prep when all are too loose), by a secant's slope where two tries give a
                # positive one, else the default
                slope = PREP_SLOPE
                if len(tries) >= 2:
                    (m1, e1), (m2, e2) = sorted(tries, key=lambda t: abs(t[1] - target))[:2]
                    if abs(m2 - m1) > 1e-9 and (e2 - e1) * (m2 - m1) > 0:
                        slope = (e2 - e1) / (m2 - m1)
                if not below:       # all too loose: on from the lowest friction tried
                    base_mu, base_e = min(tries)
                elif not above:     # all too dense: on from the highest
                    base_mu, base_e = max(tries)
                else:               # a bracket the noise turned round: from the closest
                    base_mu, base_e = min(tries, key=lambda t: abs(t[1] - target))
            nxt = min(PREP_MU_MAX, max(0.0, base_mu + (target - base_e) / slope))
            if any(abs(nxt - m) < 1e-4 for m, _ in tries) and 0.0 < nxt < PREP_MU_MAX:
                # a friction tried already (the packing's noise): 0.02 further the way to go
                nxt = min(PREP_MU_MAX, max(0.0, nxt + (0.02 if target > base_e else -0.02)))
            if any(abs(nxt - m) < 1e-4 for m, _ in tries):
                edge = [t for t in tries if abs(t[0] - nxt) < 1e-4][0]
                if nxt <= 0.0 and edge[1] > target:
                    fail("--void-ratio %g: the sample cannot reach this void ratio at %g MPa: even "
                         "frictionless preparation (mu_prep = 0) gives e = %.4f (too dense a target "
                         "for these sizes)" % (target, p, edge[1]))
                if nxt >= PREP_MU_MAX and edge[1] < target:
                    fail("--void-ratio %g: the sample cannot reach this void ratio at %g MPa: the "
                         "loosest preparation (mu_prep = %g) gives e = %.4f (too loose a target)"
                         % (target, p, PREP_MU_MAX, edge[1]))
                nxt = 0.5 * (nxt + base_mu)
            mu = round(nxt, 4)
        best = min(tries, key=lambda t: abs(t[1] - target))
        fail("--void-ratio %g: the sample did not reach this void ratio within %g at %g MPa in %d "
             "preparations (closest e = %.4f at mu_prep = %.4f); widen --e-tol or check the sizes"
             % (target, tol, p, len(tries), best[1], best[0]))

    # ---- shear runs ---------------------------------------------------------------------
    def run_key(self, prm, p, seed=None):
        a = self.a
        radius = "" if a.rolling_radius == "effective" else "_rr" + a.rolling_radius
        radius += "" if a.twisting == "none" else "_tw" + a.twisting
        radius += "" if a.cell == "walled" else "_" + a.cell
        return "%s_mu%s_mur%s%s_I%s_strain%s_deck%s" % (self.prep_key(p, prm["E"], seed), fmt(prm["mu"]),
                                                        fmt(prm["mur"]), radius, fmt(a.inertial),
                                                        fmt(a.strain), self.deck_key(1))

    def shear(self, prm, p, seed=None):
        key = self.run_key(prm, p, seed)
        hit = self.eval_cache.get(key)
        if hit and Path(hit["csv"]).is_file():
            return hit
        s = self.sample(p, prm["E"], seed)
        d = self.work / "runs" / key
        variables = dict(self.cell_vars(prm["E"]), prep=s["restart"], sigma3=fmt(p * 1e6), E=fmt(prm["E"]),
                         mu=fmt(prm["mu"]), mur=fmt(prm["mur"]), rolling_radius=self.a.rolling_radius,
                         inertial=fmt(self.a.inertial), strain=fmt(self.a.strain), csv="triax.csv")
        if self.a.twisting == "sds":
            k, c, m = twisting_coeffs(prm["E"], 0.1, prm["mu"], p * 1e6, self.a.void_ratio)
            variables.update(twisting="sds", ktw=fmt(k), ctw=fmt(c), mutw=fmt(m))
        out, secs = run_deck(self.decks()[1], d, variables)
        cons, shear = summary(d, "consolidated"), summary(d, "shear")
        rec = {"csv": str(d / "triax.csv"), "seconds": secs,
               "e0": cons["void_ratio"],
               "wall_err_max": max(abs(w / (p * 1e6) - 1) for w in cons["walls_Pa"][:4]),
               "inertial": shear["inertial_number"],
               "rate": shear["rate_per_s"],
               "mu_prep": s["mu_prep"]}
        self.eval_cache.put(key, rec)
        print("fit.py: run mu %.4g mur %.4g E %.3g at %g MPa (seed %d): %.0f s"
              % (prm["mu"], prm["mur"], prm["E"], p, self.a.seed if seed is None else seed, secs), flush=True)
        return rec

    def evaluate(self, prm, pool):
        """{sigma3: [the run of each seed]} of a parameter set."""
        futs = {(p, s): pool.submit(self.shear, prm, p, s) for p in self.a.pressures for s in self.seeds()}
        return {p: [futs[(p, s)].result() for s in self.seeds()] for p in self.a.pressures}
