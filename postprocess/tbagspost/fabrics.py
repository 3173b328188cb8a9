"""The design presets (cyclic, stack) run with two fabrics (inputs/fabric.lmp): their isolator
properties side by side, and the ratio of one fabric's to the other's as the model's uncertainty
from the fabric (which the paper leaves open). Reads each fabric's figures/cyclic_table.csv and
figures/ro_parameters.csv (tbagspost.cyclic.write) and writes fabrics.md and fabrics.csv.

python3 -m tbagspost.fabrics OUT FABRIC=FIGURES_DIR FABRIC=FIGURES_DIR
"""
import csv
import sys
from pathlib import Path


def read(path):
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


def last_cycles(rows):
    """{(run, nominal amplitude): the row of the amplitude's last cycle}."""
    out = {}
    for r in rows:
        key = (r["run"], float(r["ua_nominal_mm"]))
        if key not in out or int(r["cycle"]) > int(out[key]["cycle"]):
            out[key] = r
    return out


def compare(figures):
    """figures: {fabric: folder}, two fabrics. Returns (rows of K_eq and h_eq per run and
    amplitude, rows of the R-O parameters per run), each with both fabrics' values and the ratio
    second / first (h_eq: the difference)."""
    (fa, da), (fb, db) = list(figures.items())[:2]
    ta, tb = last_cycles(read(Path(da) / "cyclic_table.csv")), last_cycles(read(Path(db) / "cyclic_table.csv"))
    cyc = []
    for key in sorted(set(ta) & set(tb), key=lambda k: (k[0], k[1])):
        a, b = ta[key], tb[key]
        ka, kb = float(a["K_eq_N_per_mm"]), float(b["K_eq_N_per_mm"])
        ha, hb = float(a["h_eq"]), float(b["h_eq"])
        cyc.append(dict(run=key[0], ua_mm=key[1], **{"K_eq_%s" % fa: ka, "K_eq_%s" % fb: kb, "K_ratio": kb / ka,
                                                      "h_eq_%s" % fa: ha, "h_eq_%s" % fb: hb, "h_diff": hb - ha}))
    ra = {r["run"]: r for r in read(Path(da) / "ro_parameters.csv")}
    rb = {r["run"]: r for r in read(Path(db) / "ro_parameters.csv")}
    ro = []
    for run in [r for r in ra if r in rb]:
        row = dict(run=run)
        for p in ("K0_N_per_mm", "Sy_N", "r"):
            x, y = float(ra[run][p]), float(rb[run][p])
            row.update({"%s_%s" % (p, fa): x, "%s_%s" % (p, fb): y, "%s_ratio" % p: y / x})
        ro.append(row)
    return fa, fb, cyc, ro


def report(fa, fb, cyc, ro):
    lines = ["# The isolator's properties with two bag fabrics: %s and %s" % (fa, fb), "",
             "The fabric decides how much of the load the bag's walls carry (./tbags fabric, "
             "results/README.md): the paper leaves it open, so the ratio %s/%s is the model's "
             "uncertainty from it. Design with the range, or settle it with the bag's vertical "
             "stiffness under load in the laboratory." % (fb, fa), "",
             "## Ramberg-Osgood parameters", "",
             "| run | K_0 %s (N/mm) | K_0 %s | ratio | S_y %s (N) | S_y %s | ratio | r %s | r %s |" % (fa, fb, fa, fb, fa, fb),
             "|---|---|---|---|---|---|---|---|---|"]
    for r in ro:
        lines.append("| %s | %.1f | %.1f | %.2f | %.1f | %.1f | %.2f | %.2f | %.2f |" % (
            r["run"], r["K0_N_per_mm_" + fa], r["K0_N_per_mm_" + fb], r["K0_N_per_mm_ratio"],
            r["Sy_N_" + fa], r["Sy_N_" + fb], r["Sy_N_ratio"], r["r_" + fa], r["r_" + fb]))
    lines += ["", "## K_eq and h_eq per amplitude (the last cycle)", "",
              "| run | u_a (mm) | K_eq %s (N/mm) | K_eq %s | ratio | h_eq %s | h_eq %s | difference |" % (fa, fb, fa, fb),
              "|---|---|---|---|---|---|---|---|"]
    for c in cyc:
        lines.append("| %s | %g | %.1f | %.1f | %.2f | %.3f | %.3f | %+.3f |" % (
            c["run"], c["ua_mm"], c["K_eq_" + fa], c["K_eq_" + fb], c["K_ratio"], c["h_eq_" + fa],
            c["h_eq_" + fb], c["h_diff"]))
    return "\n".join(lines) + "\n"


def write(out, figures):
    fa, fb, cyc, ro = compare(figures)
    out = Path(out)
    text = report(fa, fb, cyc, ro)
    (out / "fabrics.md").write_text(text)
    if cyc:
        with open(out / "fabrics.csv", "w", newline="") as fh:
            w = csv.DictWriter(fh, fieldnames=list(cyc[0]))
            w.writeheader()
            w.writerows(cyc)
    return text


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if len(argv) != 3 or any("=" not in a for a in argv[1:]):
        sys.exit(__doc__.strip().splitlines()[-1])
    figures = dict(a.split("=", 1) for a in argv[1:])
    print(write(argv[0], figures), end="")


if __name__ == "__main__":
    main()
