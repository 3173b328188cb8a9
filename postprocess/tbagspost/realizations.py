"""Several realizations of one shear test (fills of different seeds, the same protocol): their
spread. A filled bag is one random packing; one run is one sample.

For each group of realizations (one load): the mean S-u and w-u curves on a common u grid with
+-1 standard deviation and the min-max envelope over the realizations, and per realization the
figures a paper reports: peak S and its u, S at u = 5 mm (where T-BAGS works; the row whose
0.1 mm holds it), S and u of the last row, the contraction
(w at the start of shearing minus the lowest w) and the dilatancy (w at the end minus the lowest
w), with their mean, standard deviation (n - 1) and range.
Writes into OUTDIR: realizations.csv (one row per run), realizations.md (the table with the
spread), curves_<group>.csv (u_mm, S and w: mean, std, min, max, n) and realizations.png.
"""
import os
import re
from collections import OrderedDict
from pathlib import Path

import numpy as np

from tbagspost import fail, style

U_DESIGN = 5.0     # mm: T-BAGS works up to 5 mm of displacement
METRICS = OrderedDict([
    ("S_peak_N", "peak S (N)"),
    ("u_peak_mm", "u at peak S (mm)"),
    ("S_5mm_N", "S at u = 5 mm (N)"),
    ("contraction_mm", "contraction (mm)"),
    ("dilatancy_mm", "dilatancy (mm)"),
    ("S_end_N", "S at the end (N)"),
    ("u_end_mm", "u at the end (mm)"),
    ("Fv_N", "F_v, mean while shearing (N)"),
])


def metrics(d):
    """The reported figures of one run's CSV (structured array of in.shear's shear.csv)."""
    u, S, w = d["u_mm"], d["S_N"], d["w_mm"] - d["w_mm"][0]
    du = float(np.median(np.diff(u[1:]))) if len(u) > 2 else 0.0
    k = int(np.argmax(S))
    kmin = int(np.argmin(w))
    return OrderedDict([
        ("S_peak_N", float(S[k])),
        ("u_peak_mm", float(u[k])),
        # the row whose interval holds u = 5 mm (a run to 5 mm: its last row, centred at 4.95)
        ("S_5mm_N", float(np.interp(U_DESIGN, u, S)) if u[-1] + 0.5 * du >= U_DESIGN - 1e-2 else float("nan")),
        ("contraction_mm", float(-w[kmin])),
        ("dilatancy_mm", float(w[-1] - w[kmin])),
        ("S_end_N", float(S[-1])),
        ("u_end_mm", float(u[-1])),
        ("Fv_N", float(np.mean(d["Fv_N"][1:]))),
    ])


def spread(values):
    """mean, standard deviation (n - 1; 0 for one value), min, max of the finite values."""
    v = np.asarray([x for x in values if np.isfinite(x)], dtype=float)
    if len(v) == 0:
        return (float("nan"),) * 4
    return (float(v.mean()), float(v.std(ddof=1)) if len(v) > 1 else 0.0, float(v.min()), float(v.max()))


def mean_curves(csvs, n=201):
    """S and w (from the start of shearing) of the runs on a common u grid from 0 to the smallest
    final u: dict of u_mm and, for S_N and w_mm, mean, std, min, max over the runs."""
    umax = min(float(d["u_mm"][-1]) for d in csvs)
    grid = np.linspace(0.0, umax, n)
    out = OrderedDict(u_mm=grid)
    for col in ("S_N", "w_mm"):
        ys = np.array([np.interp(grid, d["u_mm"], d[col] - (d[col][0] if col == "w_mm" else 0.0))
                       for d in csvs])
        out[col + "_mean"] = ys.mean(axis=0)
        out[col + "_std"] = ys.std(axis=0, ddof=1) if len(csvs) > 1 else np.zeros(n)
        out[col + "_min"] = ys.min(axis=0)
        out[col + "_max"] = ys.max(axis=0)
    return out


def group_runs(runs):
    """Runs grouped by their directory name when names repeat (r1/F5500, r2/F5500: group F5500),
    else all in one group 'all'."""
    names = [r.name for r in runs]
    if len(set(names)) == len(names):
        return OrderedDict(all=list(runs))
    groups = OrderedDict()
    for r in runs:
        groups.setdefault(r.name, []).append(r)
    return groups


def realization_dir(run):
    """The realization's folder: the run's own for a run per realization (r1), else its parent
    (r1/F5500 a load, r1/v0.01 a speed of a realization)."""
    here = run.path.resolve()
    return here.parent if run.name.startswith("F") or re.fullmatch(r"r\d+", here.parent.name) else here


def realization_name(run):
    return realization_dir(run).name


def table_md(groups, rows):
    """Markdown table: per group and metric, mean +- std [min, max] (n)."""
    lines = ["| group | realizations | " + " | ".join(METRICS.values()) + " |",
             "|---|---|" + "---|" * len(METRICS)]
    for g in groups:
        mine = [r for r in rows if r["group"] == g]
        cells = []
        for key in METRICS:
            m, s, lo, hi = spread([r[key] for r in mine])
            cells.append("n/a" if not np.isfinite(m) else "%.3g +- %.2g [%.3g, %.3g]" % (m, s, lo, hi))
        lines.append("| %s | %d | %s |" % (g, len(mine), " | ".join(cells)))
    return "\n".join(lines)


def figure(curves):
    """Mean S-u and w-u with +-1 std (shaded) and the min-max envelope (thin) per group."""
    fig, (a_s, a_w) = style.figure(1, 2, width=7.0, height=2.8)
    cycle = style.PAPER["axes.prop_cycle"].by_key()
    for k, (g, c) in enumerate(curves.items()):
        u = c["u_mm"]
        col, ls = cycle["color"][k % len(cycle["color"])], cycle["linestyle"][k % len(cycle["linestyle"])]
        a_s.plot(u, c["S_N_mean"] / 1000, color=col, linestyle=ls, label="%s (n = %d)" % (g, c["n"]))
        a_w.plot(u, c["w_mm_mean"], color=col, linestyle=ls)
        for ax, key, scale in ((a_s, "S_N", 1000.0), (a_w, "w_mm", 1.0)):
            ax.fill_between(u, (c[key + "_mean"] - c[key + "_std"]) / scale,
                            (c[key + "_mean"] + c[key + "_std"]) / scale, color=col, alpha=0.2, lw=0)
            for env in ("_min", "_max"):
                ax.plot(u, c[key + env] / scale, color=col, linestyle="-", lw=0.5, alpha=0.6)
    a_s.set_xlabel("horizontal displacement $u$ (mm)")
    a_s.set_ylabel("shear force $S$ (kN)")
    a_w.set_xlabel("horizontal displacement $u$ (mm)")
    a_w.set_ylabel("vertical displacement $w$ (mm)")
    a_w.axhline(0, color="0.5", lw=0.6)
    a_s.legend(loc="lower right", frameon=False)
    for ax, tag in ((a_s, "(a)"), (a_w, "(b)")):
        ax.set_xlim(left=0)
        style.panel_label(ax, tag)
    fig.suptitle("mean of the realizations, $\\pm$1 standard deviation (shaded), min and max (thin)")
    fig.tight_layout()
    return fig


def write(runs, outdir):
    """The realizations' table, curves and figure into outdir; returns the Markdown table."""
    if len(runs) < 2:
        fail("realizations: give at least two runs (got %d)" % len(runs))
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    groups = group_runs(runs)
    rows, curves = [], OrderedDict()
    for g, members in groups.items():
        for r in members:
            rows.append(OrderedDict([("group", g), ("realization", realization_name(r)),
                                     ("run", os.path.relpath(r.path.resolve(), outdir.resolve().parent)),
                                     ] + list(metrics(r.csv).items())))
        c = mean_curves([r.csv for r in members])
        c["n"] = len(members)
        curves[g] = c
        cols = [k for k in c if k != "n"]
        np.savetxt(outdir / ("curves_%s.csv" % g), np.column_stack([c[k] for k in cols]),
                   delimiter=",", header=",".join(cols), comments="", fmt="%.6g")
    keys = list(rows[0].keys())
    with open(outdir / "realizations.csv", "w") as f:
        f.write(",".join(keys) + "\n")
        for r in rows:
            f.write(",".join(r[k] if isinstance(r[k], str) else "%.6g" % r[k] for k in keys) + "\n")
    md = table_md(groups, rows)
    (outdir / "realizations.md").write_text(
        "# Realizations: mean +- standard deviation (n - 1) [min, max]\n\n" + md + "\n\n"
        "Per run: realizations.csv. Curves (mean, std, min, max on a common u grid): curves_*.csv.\n")
    style.save(figure(curves), outdir / "realizations", ("png",))
    return md
