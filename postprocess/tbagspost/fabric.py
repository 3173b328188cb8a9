"""What the fabric carries alone: the force-gap curves of inputs/in.press on an empty bag (in.fill
-var per_size 1: ten grains) and on the filled bag, per fabric.

The filled bag reaches the load F_v at the gap g_f between the plates (the first row of its
curve at or above F_v, interpolated); the empty bag's force at that same gap, over F_v, is the
share of the load the fabric could carry without sand. A woven bag should carry almost none: its
walls fold. Figure: the curves (force against gap over the bag's height) and side views of each
empty bag at the dump nearest g_f and at its last dump (half the height).
"""
from pathlib import Path

import numpy as np

from tbagspost import dumps, style


def read_press(path):
    """(gap mm, F_v N, header dict) of a press.csv; the header line gives gap0_mm, H_mm, fabric."""
    lines = Path(path).read_text().splitlines()
    head = lines[0].lstrip("# ").split()
    meta = dict(zip(head[1::2], head[2::2]))
    rows = [line for line in lines[1:] if line and not line.startswith("#")]
    names = rows[0].split(",")
    data = np.array([[float(x) for x in r.split(",")] for r in rows[1:]])
    col = {n: data[:, k] for k, n in enumerate(names)}
    return col["gap_mm"], col["Fv_N"], meta


def gap_at(gap, force, target):
    """The gap (mm) where the force first reaches target as the plate moves down (linear between
    rows); None if it never does."""
    above = np.nonzero(force >= target)[0]
    if len(above) == 0:
        return None
    k = above[0]
    if k == 0:
        return float(gap[0])
    return float(np.interp(target, [force[k - 1], force[k]], [gap[k - 1], gap[k]]))


def force_at(gap, force, g):
    """The force (N) at gap g (linear between rows; 0 above the first row, where no plate touched)."""
    if g >= gap[0]:
        return 0.0
    return float(np.interp(-g, -gap, force))


def alone(empty_csv, filled_csv, Fv):
    """The numbers of one fabric: dict with the filled bag's gap at F_v, the empty bag's force
    there and its share of F_v, and the empty bag's force at its last row."""
    ge, Fe, meta = read_press(empty_csv)
    gf, Ff, _ = read_press(filled_csv)
    g = gap_at(gf, Ff, Fv)
    if g is None:
        raise ValueError("%s: the filled bag never reaches F_v = %g N (largest %.1f N)" % (filled_csv, Fv, Ff.max()))
    fe = force_at(ge, Fe, g)
    return dict(fabric=meta.get("fabric", "?"), H_mm=float(meta["H_mm"]), Fv=Fv, gap_filled_mm=g,
                F_empty=fe, share=fe / Fv, gap_end_mm=float(ge[-1]), F_empty_end=float(Fe[-1]))


def describe(r):
    return ("fabric %s: the filled bag reaches F_v = %.1f N at a gap of %.2f mm (%.1f %% of its height); "
            "the empty bag carries %.2f N there, %.1f %% of F_v; at %.2f mm (%.0f %% of the height) %.0f N"
            % (r["fabric"], r["Fv"], r["gap_filled_mm"], 100 * r["gap_filled_mm"] / r["H_mm"], r["F_empty"],
               100 * r["share"], r["gap_end_mm"], 100 * r["gap_end_mm"] / r["H_mm"], r["F_empty_end"]))


def walls(ax, folder, g_mm, title):
    """Side view (x-z) of the bag particles of the dump in folder nearest the gap g_mm, with the
    plates; sand grains in grey."""
    steps = sorted(int(p.name.rsplit(".", 1)[1]) for p in Path(folder).glob("dump.grains.*")
                   if p.name.rsplit(".", 1)[1].isdigit())
    gap, _, meta = read_press(Path(folder) / "press.csv")
    # dumps every quarter of the travel from the first row: their gaps in order
    gaps = np.linspace(gap[0], gap[-1], len(steps)) if len(steps) > 1 else gap[:1]
    k = int(np.argmin(np.abs(gaps - g_mm)))
    gr = dumps.read_grains(Path(folder) / ("dump.grains.%d" % steps[k]))
    y = gr.pos[:, 1]
    mid = np.abs(y - np.median(y[gr.bag])) < 0.0026
    for mask, kw in ((mid & ~gr.bag, dict(color="0.7", s=6)), (mid & gr.bag, dict(color="C0", s=8))):
        ax.scatter(gr.pos[mask, 0] * 1e3, gr.pos[mask, 2] * 1e3, **kw)
    zbot = -2.5
    for z in (zbot, zbot + gaps[k]):
        ax.axhline(z, color="k", lw=2)
    ax.set_aspect("equal")
    ax.set_title("%s, gap %.1f mm" % (title, gaps[k]), fontsize=8)
    ax.set_xlabel("x (mm)")


def figure(results, folders):
    """results: alone() per fabric; folders: {fabric: (empty_folder, filled_folder)}."""
    n = len(results)
    fig, gs = style.grid_figure(2, max(n, 1) * 2, 3.2 * n + 1, 5.6)
    ax = fig.add_subplot(gs[0, :])
    for k, r in enumerate(results):
        e, f = folders[r["fabric"]]
        for folder, ls, what in ((f, "-", "filled"), (e, ":", "empty")):
            g, F, _ = read_press(Path(folder) / "press.csv")
            ax.plot(g / r["H_mm"], F, color="C%d" % k, ls=ls, label="%s, %s" % (r["fabric"], what))
        ax.plot(r["gap_filled_mm"] / r["H_mm"], r["Fv"], "o", color="C%d" % k, ms=4)
    ax.axhline(results[0]["Fv"], color="0.5", lw=0.8, label="F_v (the demo's stress)")
    ax.set_yscale("symlog", linthresh=max(1.0, results[0]["Fv"] / 10))
    ax.set_ylim(bottom=0)
    ax.set_xlabel("gap between the plates / the bag's height")
    ax.set_ylabel("F_v (N)")
    ax.invert_xaxis()
    ax.legend(ncol=2, fontsize=7)
    style.panel_label(ax, "(a)")
    for k, r in enumerate(results):
        e, _ = folders[r["fabric"]]
        walls(fig.add_subplot(gs[1, 2 * k]), e, r["gap_filled_mm"], "%s empty" % r["fabric"])
        walls(fig.add_subplot(gs[1, 2 * k + 1]), e, r["gap_end_mm"], "%s empty" % r["fabric"])
    return fig


def main(argv=None):
    """python3 -m tbagspost.fabric OUT --Fv N --pair FABRIC EMPTY_DIR FILLED_DIR [...]: the
    numbers (printed), OUT/fabric-alone.csv and OUT/fabric-alone.png."""
    import argparse
    ap = argparse.ArgumentParser(prog="python3 -m tbagspost.fabric")
    ap.add_argument("out", type=Path)
    ap.add_argument("--Fv", type=float, required=True)
    ap.add_argument("--pair", nargs=3, action="append", required=True, metavar=("FABRIC", "EMPTY", "FILLED"))
    a = ap.parse_args(argv)
    results, folders = [], {}
    for fabric, empty, filled in a.pair:
        r = alone(Path(empty) / "press.csv", Path(filled) / "press.csv", a.Fv)
        r["fabric"] = fabric
        results.append(r)
        folders[fabric] = (empty, filled)
        print(describe(r))
    keys = ("fabric", "H_mm", "Fv", "gap_filled_mm", "F_empty", "share", "gap_end_mm", "F_empty_end")
    lines = [",".join(keys)] + [",".join(str(r[k]) if k == "fabric" else "%.6g" % r[k] for k in keys) for r in results]
    (a.out / "fabric-alone.csv").write_text("\n".join(lines) + "\n")
    written = style.save(figure(results, folders), a.out / "fabric-alone")
    print("wrote %s and %s" % (a.out / "fabric-alone.csv", written[0]))


if __name__ == "__main__":
    main()
