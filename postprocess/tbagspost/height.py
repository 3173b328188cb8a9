"""The height study: bags of one plan-to-height ratio and one vertical stress, compared at equal
shear strain u/H (H: the sand's height inside the bag), so that a smaller bag can be judged
against a taller one (the paper's: 75 mm of sand).

  python3 -m tbagspost.height [--strains 5,10,15,20] [--ref LABEL] [-o FILE.md]
                              LABEL:H_MM:CSV[+CSV...] ...

Each bag: a label, its sand height in mm, and one shear CSV (inputs/in.shear) or several, one
per realization, joined by '+'. At each strain, per CSV: S/F_v (both the means of the CSV rows,
taken at u = strain x H, linear between rows) and w/H in % (w from the row u = 0, the compressed
state; w < 0: contraction); several CSVs give mean +- standard deviation. The reference bag
(--ref, default the tallest) judges the others: the largest relative difference of S/F_v and the
largest difference of w/H over the strains both reached, and whether S/F_v is within 10 % of the
reference at every such strain. A strain beyond a CSV's last row (by more than half a row's
interval) is left out ("-").
"""
import sys
from pathlib import Path

import numpy as np

from tbagspost import fail
from tbagspost.run import read_csv

WITHIN = 0.10    # relative difference of S/F_v that makes a smaller bag stand for the reference


def parse_bag(text):
    """'LABEL:H_MM:CSV[+CSV...]' -> (label, H in mm, [paths])."""
    parts = text.split(":", 2)
    if len(parts) != 3 or not parts[0] or not parts[2]:
        fail("a bag is LABEL:H_MM:CSV[+CSV...], not '%s'" % text)
    try:
        h = float(parts[1])
    except ValueError:
        h = float("nan")
    if not np.isfinite(h) or h <= 0:
        fail("bag %s: its sand height must be a positive number of mm, not '%s'" % (parts[0], parts[1]))
    return parts[0], h, [Path(p) for p in parts[2].split("+")]


def at_strain(d, h_mm, strain_pct):
    """(S/F_v, w/H in %) of one shear CSV at u = strain x H, or (nan, nan) past its last row (a
    row is the mean over its interval: the last one stands for u up to half an interval on)."""
    u = strain_pct / 100.0 * h_mm
    if u > d["u_mm"][-1] + 0.5 * (d["u_mm"][-1] - d["u_mm"][-2]) + 1e-9:
        return float("nan"), float("nan")
    s = np.interp(u, d["u_mm"], d["S_N"])
    fv = np.interp(u, d["u_mm"], d["Fv_N"])
    w = np.interp(u, d["u_mm"], d["w_mm"]) - d["w_mm"][0]
    return float(s / fv), float(100.0 * w / h_mm)


def measure(bags, strains):
    """{label: {"H": mm, "n": CSVs, "ratio": [(mean, sd)], "w": [(mean, sd)]}} per strain; sd is
    nan for one CSV; a strain some CSV did not reach is (nan, nan)."""
    out = {}
    for label, h, paths in bags:
        vals = np.array([[at_strain(read_csv(p), h, s) for s in strains] for p in paths])
        res = {"H": h, "n": len(paths)}
        for k, key in enumerate(("ratio", "w")):
            col = vals[:, :, k]
            sd = col.std(axis=0, ddof=1) if len(paths) > 1 else np.full(len(strains), np.nan)
            res[key] = list(zip(col.mean(axis=0), sd))
        out[label] = res
    return out


def compare(m, ref):
    """{label: (largest |rel. diff.| of S/F_v, largest |diff.| of w/H in %, within 10 % or None
    when no strain is shared)} against the reference bag."""
    out = {}
    for label, r in m.items():
        if label == ref:
            continue
        dr = [abs(a[0] / b[0] - 1) for a, b in zip(r["ratio"], m[ref]["ratio"])
              if np.isfinite(a[0]) and np.isfinite(b[0])]
        dw = [abs(a[0] - b[0]) for a, b in zip(r["w"], m[ref]["w"]) if np.isfinite(a[0]) and np.isfinite(b[0])]
        out[label] = (max(dr), max(dw), max(dr) <= WITHIN) if dr else (float("nan"), float("nan"), None)
    return out


def cell(v):
    mean, sd = v
    if not np.isfinite(mean):
        return "-"
    return "%.3g" % mean if not np.isfinite(sd) else "%.3g +- %.2g" % (mean, sd)


def report(bags, strains, ref=None):
    """The markdown tables of the study."""
    m = measure(bags, strains)
    ref = ref or max(m, key=lambda k: m[k]["H"])
    if ref not in m:
        fail("--ref %s is none of the bags (%s)" % (ref, ", ".join(m)))
    head = "| shear strain u/H | " + " | ".join("%g %%" % s for s in strains) + " |"
    lines = [head, "|---|" + "---|" * len(strains)]
    for key, name in (("ratio", "S/F_v"), ("w", "w/H (%)")):
        for label, r in m.items():
            n = " (%d realizations)" % r["n"] if r["n"] > 1 else ""
            lines.append("| %s, %s (H %g mm)%s | " % (name, label, r["H"], n)
                         + " | ".join(cell(v) for v in r[key]) + " |")
    lines += ["", "Against %s (H %g mm), over the strains both reached:" % (ref, m[ref]["H"]), "",
              "| bag | largest S/F_v difference | largest w/H difference (%% of H) | S/F_v within %d %% |"
              % round(100 * WITHIN), "|---|---|---|---|"]
    for label, (dr, dw, ok) in compare(m, ref).items():
        lines.append("| %s | %s | %s | %s |" % (
            label, "-" if ok is None else "%.1f %%" % (100 * dr), "-" if ok is None else "%.2f" % dw,
            {True: "yes", False: "no", None: "no shared strain"}[ok]))
    return "\n".join(lines) + "\n"


def main(argv=None):
    argv = list(sys.argv[1:] if argv is None else argv)
    strains, ref, out, bags = [5.0, 10.0, 15.0, 20.0], None, None, []
    while argv:
        a = argv.pop(0)
        if a in ("--strains", "--ref", "-o") and not argv:
            fail("%s needs a value" % a)
        if a == "--strains":
            try:
                strains = [float(s) for s in argv.pop(0).split(",")]
            except ValueError:
                fail("--strains takes numbers in %, comma-separated (5,10,15,20)")
            if any(not np.isfinite(s) or s <= 0 for s in strains):
                fail("--strains must be positive percentages")
        elif a == "--ref":
            ref = argv.pop(0)
        elif a == "-o":
            out = Path(argv.pop(0))
        elif a.startswith("-"):
            fail("unknown option %s (python3 -m tbagspost.height --help)" % a if a not in ("-h", "--help")
                 else __doc__.strip())
        else:
            bags.append(parse_bag(a))
    if len(bags) < 2:
        fail("give two bags or more (python3 -m tbagspost.height --help)")
    text = report(bags, strains, ref)
    if out:
        out.write_text(text)
    print(text, end="")
    return 0


if __name__ == "__main__":
    sys.exit(main())
