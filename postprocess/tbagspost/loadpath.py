"""What carries the load: the forces passed across a horizontal plane at the bag's mid-height,
split into sand-sand, bag-sand and bag-bag contacts and the yarn bonds.

The plane lies halfway between the two middle layers of the bag's grid (filled-state heights are
multiples of the 5 mm spacing), at their current mean height, so that no wall particle sits on
it. A contact or bond crosses it when its two particles lie on either side. What crosses it is,
on the part below, the top plate's F_v (plus the weight above) downward and its S along x (less
the inertia of the part above, small in a quasi-static run): the contacts push, the bonds pull
(axially, and through the shear spring of the solid fabric). The bonds' forces come from the
bond dump's fbx fby fbz (the bond's whole force on its atom of lower id; inputs/in.shear since the
fabric study); without them the bonds are left out and their share is the remainder. A sandbag
whose sand is loaded shows most of F_v in sand contacts.
"""
import json
import sys
from collections import OrderedDict

import numpy as np

from .run import Run

SPACING = 0.005    # m, the bag grid
CLASSES = ("sand-sand", "bag-sand", "bag-bag", "bonds")
KEPT = "loadpath.kept.json"    # the load path of dump steps whose dumps may be dropped (keep())


def mid_plane(g):
    """Height (m) of the plane halfway between the bag's two middle grid layers."""
    z0 = g.pos[:, 2] - g.disp[:, 2]
    bag = g.bag
    layer = np.rint((z0[bag] - z0[bag].min()) / SPACING).astype(int)
    below = (layer.max() - 1) // 2
    z = g.pos[bag, 2]
    return 0.5 * (z[layer == below].mean() + z[layer == below + 1].mean())


def _sums(f_low, cross):
    """(compressive vertical, x) force (N) on the part below, of the crossing rows of f_low."""
    return float(-f_low[cross, 2].sum()), float(f_low[cross, 0].sum())


def through_plane(g, c, z=None, b=None):
    """Forces passed across the plane z (default mid_plane) by the contacts c and the bonds b (a
    bond dump with fbx fby fbz, or None): OrderedDict with z, the total vertical (compressive, N)
    and horizontal x force (N, on the part below) and, per class sand-sand / bag-sand / bag-bag /
    bonds, those two and the number crossing; 'bonds' is None without b."""
    z = mid_plane(g) if z is None else z
    i1, i2 = g.index(c["id1"]), g.index(c["id2"])
    p1, p2 = g.pos[i1], g.pos[i2]
    cross = (p1[:, 2] - z) * (p2[:, 2] - z) < 0
    d = p1 - p2
    n = d / np.linalg.norm(d, axis=1)[:, None]
    f1 = c["fn"][:, None] * n + np.column_stack([c["ftx"], c["fty"], c["ftz"]])    # force on 1
    f_low = np.where((p1[:, 2] > p2[:, 2])[:, None], -f1, f1)      # on the lower particle
    t1, t2 = c["type1"], c["type2"]
    classes = OrderedDict([("sand-sand", (t1 == 2) & (t2 == 2)), ("bag-sand", t1 != t2),
                           ("bag-bag", (t1 == 1) & (t2 == 1))])
    out = OrderedDict(z=float(z))
    for name, m in classes.items():
        out[name] = _sums(f_low, cross & m) + (int((cross & m).sum()),)
    out["bonds"] = None
    if b is not None and "fbx" in b:
        lo_id, hi_id = np.minimum(b["id1"], b["id2"]), np.maximum(b["id1"], b["id2"])
        pl, ph = g.pos[g.index(lo_id)], g.pos[g.index(hi_id)]
        bcross = (pl[:, 2] - z) * (ph[:, 2] - z) < 0
        f_lo = np.column_stack([b["fbx"], b["fby"], b["fbz"]])    # on the atom of lower id
        f_low = np.where((pl[:, 2] > ph[:, 2])[:, None], -f_lo, f_lo)
        out["bonds"] = _sums(f_low, bcross) + (int(bcross.sum()),)
    parts = [out[k] for k in CLASSES if out[k] is not None]
    out["Fz"] = sum(p[0] for p in parts)
    out["Fx"] = sum(p[1] for p in parts)
    return out


def describe(r, S=None, Fv=None):
    """One line: the share of F_v and of S per class (of the plate's F_v and S when given)."""
    Fz = Fv or r["Fz"]
    have = [k for k in CLASSES if r[k] is not None]
    share = ", ".join("%s %.0f %%" % (k, 100 * r[k][0] / Fz) for k in have)
    line = ("load path at mid-height (z = %.1f mm): vertical %.0f N across it%s: %s"
            % (r["z"] * 1e3, r["Fz"], " (F_v %.0f N)" % Fv if Fv else "", share))
    if S:
        line += "; horizontal %.0f N of S = %.0f N: %s" % (r["Fx"], S, ", ".join(
            "%s %.0f %%" % (k, 100 * r[k][1] / S) for k in have))
        if r["bonds"] is None:
            line += " (the rest through the yarn bonds)"
    return line


def at_step(run, step):
    """through_plane() of a shear run's dump step, with its bonds where their dump exists."""
    b = run.bonds(step) if run.dump("bonds", step).exists() else None
    return through_plane(run.grains(step), run.contacts(step), b=b)


def kept(run):
    """{step: through_plane result} kept in the run's KEPT file (keep()), or {}."""
    path = run.path / KEPT
    if not path.is_file():
        return {}
    return {int(step): OrderedDict((k, tuple(v) if isinstance(v, list) else v) for k, v in r)
            for step, r in json.loads(path.read_text()).items()}


def keep(run):
    """Write at_step() of every dump step of the run, with those kept before, to its KEPT file, so
    that the dumps can be dropped (a run carried between machines, states/README.md) and the load
    path still has their rows; returns the steps kept."""
    rows = by_step(run)
    (run.path / KEPT).write_text(json.dumps({str(s): list(r.items()) for s, r in rows.items()}) + "\n")
    return list(rows)


def by_step(run):
    """at_step() of every dump step of a shear run, in order; the kept rows (keep()) of steps
    whose dumps are gone."""
    rows = kept(run)
    rows.update((step, at_step(run, step)) for step in run.steps("contacts"))
    return OrderedDict((step, rows[step]) for step in sorted(rows))


def main(argv=None):
    """python3 -m tbagspost.loadpath keep RUN_DIR ...: keep() of each run."""
    argv = sys.argv[1:] if argv is None else argv
    if len(argv) < 2 or argv[0] != "keep":
        raise SystemExit("usage: python3 -m tbagspost.loadpath keep RUN_DIR ...")
    for d in argv[1:]:
        steps = keep(Run(d))
        print("%s: the load path of %d dump steps kept in %s" % (d, len(steps), KEPT))


def table(run, found=None):
    """The load path at every dump step of a shear run (found: by_step(run), if already made):
    rows of u (mm), the plate's F_v and S (N), the vertical and horizontal totals across the plane
    and each class's (N)."""
    rows = []
    for step, r in (found if found is not None else by_step(run)).items():
        row = OrderedDict(u_mm=run.at_step(step), Fv_N=run.at_step(step, "Fv_N"), S_N=run.at_step(step, "S_N"),
                          Fz_N=r["Fz"], Fx_N=r["Fx"])
        for k in CLASSES:
            v = r[k] if r[k] is not None else (float("nan"), float("nan"), 0)
            key = k.replace("-", "_")
            row["Fz_%s_N" % key], row["Fx_%s_N" % key] = v[0], v[1]
        rows.append(row)
    return rows


def write_csv(rows, path):
    """rows of table() as a CSV (one header line, %.4f)."""
    if not rows:
        return
    lines = [",".join(rows[0])] + [",".join("%.4f" % v for v in r.values()) for r in rows]
    path.write_text("# the load path across the bag's mid-height at each dump (tbagspost.loadpath): "
                    "compressive vertical Fz and x force Fx on the part below, N\n" + "\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
