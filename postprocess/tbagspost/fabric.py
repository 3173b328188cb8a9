"""What the fabric carries alone: the force-gap curves of inputs/in.press on an empty bag (in.fill
-var per_size 1: ten grains) and on the filled bag, per fabric.

The filled bag reaches the load F_v at the gap g_f between the plates (the first row of its
curve at or above F_v, interpolated); the empty bag's force at that same gap, over F_v, is the
share of the load the fabric could carry without sand. A woven bag should carry almost none: its
walls fold. Figure: the curves (force against gap over the bag's height) and side views of each
empty bag at the dump nearest g_f and at its last dump (half the height).
"""
import math
from pathlib import Path

import numpy as np

from tbagspost import dumps, style


def read_press(path):
    """(columns, header dict) of a press.csv: {name: array} (gap_mm, Fv_N, ..., broken_bonds);
    the header line gives gap0_mm, H_mm, fabric."""
    lines = Path(path).read_text().splitlines()
    head = lines[0].lstrip("# ").split()
    meta = dict(zip(head[1::2], head[2::2]))
    rows = [line for line in lines[1:] if line and not line.startswith("#")]
    names = rows[0].split(",")
    data = np.array([[float(x) for x in r.split(",")] for r in rows[1:]])
    return {n: data[:, k] for k, n in enumerate(names)}, meta


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
    e, meta = read_press(empty_csv)
    f, _ = read_press(filled_csv)
    ge, Fe, gf, Ff = e["gap_mm"], e["Fv_N"], f["gap_mm"], f["Fv_N"]
    g = gap_at(gf, Ff, Fv)
    if g is None:
        raise ValueError("%s: the filled bag never reaches F_v = %g N (largest %.1f N)" % (filled_csv, Fv, Ff.max()))
    fe = force_at(ge, Fe, g)
    return dict(fabric=meta.get("fabric", "?"), H_mm=float(meta["H_mm"]), Fv=Fv, gap_filled_mm=g,
                F_empty=fe, share=fe / Fv, gap_end_mm=float(ge[-1]), F_empty_end=float(Fe[-1]))


YARN_TABLE = Path(__file__).resolve().parents[2] / "inputs" / "yarn_pp_tape.table"
BOND_D = 1e-3       # m, the yarn bond's diameter (inputs/yarn.lmp)
SPACING = 0.005     # m, the bag's grid


def yarn_strength(table=YARN_TABLE):
    """The bond's breaking force (N): A times the table's last stress (its break strain)."""
    rows = [line.split() for line in Path(table).read_text().splitlines()
            if len(line.split()) == 3 and line.split()[0].isdigit()]
    return math.pi * BOND_D ** 2 / 4 * float(rows[-1][2])


def matsuoka_liu(T, B, H, Kp, sigma3=0.0):
    """A soilbag's compressive strength (Pa), Matsuoka and Liu (2003): sigma_1f = K_p sigma_3 +
    (2 T / B)(K_p B / H - 1), T the bag's tensile strength per unit width (N/m), B its width and
    H its height (m), K_p = (1 + sin phi)/(1 - sin phi) of the fill."""
    return Kp * sigma3 + 2 * T / B * (Kp * B / H - 1)


def strength(press_csv):
    """(the largest row mean of F_v up to the row where the first bond broke (N), that row's gap
    in mm); None if no bond broke."""
    col, _ = read_press(press_csv)
    broke = np.nonzero(col["broken_bonds"] > 0)[0]
    if len(broke) == 0:
        return None
    k = broke[0]
    return float(col["Fv_N"][:k + 1].max()), float(col["gap_mm"][k])


def strength_check(press_csv, nx, ny, nz, Kp):
    """The measured failure load against Matsuoka and Liu's, for the inner box of an nx x ny x nz
    bag (B the mean plan side, H the height, between the particles' centre planes less one
    spacing, as in.fill's nominal volume) and T = the bond's strength per bond spacing."""
    got = strength(press_csv)
    B = math.sqrt((nx - 2) * (ny - 2)) * SPACING
    H = (nz - 2) * SPACING
    T = yarn_strength() / SPACING
    F = matsuoka_liu(T, B, H, Kp) * B * B
    return dict(F_fail=got[0] if got else None, gap_fail_mm=got[1] if got else None, F_ml=F, T=T,
                B_mm=B * 1e3, H_mm=H * 1e3, Kp=Kp, ratio=(got[0] / F) if got else None)


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
    gap = read_press(Path(folder) / "press.csv")[0]["gap_mm"]
    # dumps every quarter of the travel from the first row: their gaps in order
    gaps = np.linspace(gap[0], gap[-1], len(steps)) if len(steps) > 1 else gap[:1]
    k = int(np.argmin(np.abs(gaps - g_mm)))
    gr = dumps.read_grains(Path(folder) / ("dump.grains.%d" % steps[k]))
    y = gr.pos[:, 1]
    mid = np.abs(y - np.median(y[gr.bag])) < 0.0026
    for mask, kw in ((mid & ~gr.bag, dict(color="0.7", s=6)), (mid & gr.bag, dict(color="C0", s=8))):
        ax.scatter(gr.pos[mask, 0] * 1e3, gr.pos[mask, 2] * 1e3, **kw)
    zbot = -0.5 * SPACING * 1e3    # mm, the bottom plate (in.press)
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
            col, _ = read_press(Path(folder) / "press.csv")
            ax.plot(col["gap_mm"] / r["H_mm"], col["Fv_N"], color="C%d" % k, ls=ls, label="%s, %s" % (r["fabric"], what))
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
    ap.add_argument("--strength", nargs=2, action="append", default=[], metavar=("FABRIC", "DIR"),
                    help="a filled bag pressed until a bond broke (in.press -var until_break 1)")
    ap.add_argument("--size", nargs=3, type=int, help="the bag's nx ny nz (for --strength)")
    ap.add_argument("--sand", default="paper", help="the fill's sand set (K_p from its triaxial peak ratio)")
    a = ap.parse_args(argv)
    results, folders = [], {}
    for fabric, empty, filled in a.pair:
        r = alone(Path(empty) / "press.csv", Path(filled) / "press.csv", a.Fv)
        r["fabric"] = fabric
        results.append(r)
        folders[fabric] = (empty, filled)
        print(describe(r))
    keys = ("fabric", "H_mm", "Fv", "gap_filled_mm", "F_empty", "share", "gap_end_mm", "F_empty_end")
    if a.strength:
        from tbagspost import bounds
        Kp = bounds.peak_ratio(a.sand)
        for fabric_name, folder in a.strength:
            c = strength_check(Path(folder) / "press.csv", *a.size, Kp)
            r = next(x for x in results if x["fabric"] == fabric_name)
            r.update(strength_F=c["F_fail"], strength_ml=c["F_ml"], strength_ratio=c["ratio"])
            if c["F_fail"] is None:
                print("fabric %s: soilbag strength: no bond broke (press further: gap_final)" % fabric_name)
                continue
            print("fabric %s: soilbag strength: the first bond broke at F_v %.0f N (gap %.2f mm); Matsuoka and "
                  "Liu: %.0f N (T %.1f kN/m, B %.0f mm, H %.0f mm, K_p %.2f of the %s sand, sigma_3 0): ratio %.2f"
                  % (fabric_name, c["F_fail"], c["gap_fail_mm"], c["F_ml"], c["T"] / 1e3, c["B_mm"], c["H_mm"],
                     Kp, a.sand, c["ratio"]))
    keys = keys + tuple(k for k in ("strength_F", "strength_ml", "strength_ratio") if any(k in r for r in results))
    lines = [",".join(keys)] + [",".join(str(r[k]) if k == "fabric" else "%.6g" % (r.get(k) if r.get(k) is not None else float("nan"))
                                         for k in keys) for r in results]
    (a.out / "fabric-alone.csv").write_text("\n".join(lines) + "\n")
    written = style.save(figure(results, folders), a.out / "fabric-alone")
    print("wrote %s and %s" % (a.out / "fabric-alone.csv", written[0]))


if __name__ == "__main__":
    main()
