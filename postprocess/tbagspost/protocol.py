"""The protocol study (./tbags shear protocol): how fast the top plate may approach the bag (the
servo's speed limit while compressing, -var vmax_compress) and how short the fill's settling may
be, for the same compressed state and the same start of shear.

Variants: the folders V<k> (compressed at a speed limit of k mm/s) in the realizations r1, r2, ...
of ROOT (or in ROOT for one realization); with --fill OTHER, the slowest approach's runs of OTHER
(the same preset with a shorter settling, e.g. -var nsettle 10000 -var settle_chunk 5000) as one
more variant, "short fill". The reference is ROOT's slowest approach. Per variant, over the
realizations:
  - the compression's steps (the first CSV row's time over the time step) and w at F_v (that
    row's w: the plate's travel from its start), and w's difference from the reference run of
    the same fill (paired), also as a void ratio, (1 + e) dw / H_in with the fill's measured void
    ratio e and inner height H_in (the FILL line);
  - F_v while shearing: the largest deviation of a realization's mean of the rows from the
    target (the COMPRESSED line's);
  - S-u and w-u (w from u = 0) against the reference: the rms difference of the mean curves and
    the realizations' pooled standard deviation (rate.compare).
A variant passes when the paired mean difference of w at F_v is within the standard deviation of
w at F_v between fills (pooled with the reference's), both curves are within the spread, and F_v
is held within FV_TOL. The chosen approach is the fastest whose slower ones all pass. With
--fill, each realization's fills are compared too (settling steps, measured void ratio,
coordination), the differences against the spread between fills.
Writes ROOT/protocol.md and protocol.csv.

usage: PYTHONPATH=postprocess /usr/bin/python3 -m tbagspost.protocol ROOT [--fill OTHER]
"""
import re
import sys
from pathlib import Path

import numpy as np

from . import fail
from .check_trends import realizations
from .rate import compare
from .realizations import mean_curves
from .run import read_csv, shear_timestep

U_FROM = 0.1       # mm: the curves' comparison starts past the plate's start-up
FV_TOL = 0.001     # F_v held within 0.1 % of its target (the servo's own tolerance while shearing)
FILL_LINE = re.compile(r"^FILL .*?: (\d+) grains, .*?coordination ([0-9.]+),.*?void ratio measured "
                       r"([0-9.]+) \(inner box [0-9.]+ x [0-9.]+ x ([0-9.]+) mm\)", re.M)
SETTLED_LINE = re.compile(r"^SETTLED: after (\d+) steps", re.M)
COMPRESSED_LINE = re.compile(r"^COMPRESSED: F_v ([0-9.]+) N \(target ([0-9.]+)\)", re.M)


def _search(pattern, path, what):
    path = Path(path)
    m = pattern.search(path.read_text(errors="replace")) if path.is_file() else None
    if not m:
        fail("protocol: no %s line in %s" % (what, path))
    return m


def fill_state(realization):
    """The realization's fill: settling steps, measured void ratio, coordination, inner height (mm)."""
    log = Path(realization) / "log.fill"
    m = _search(FILL_LINE, log, "FILL")
    return dict(settle=int(_search(SETTLED_LINE, log, "SETTLED").group(1)), e=float(m.group(3)),
                coordination=float(m.group(2)), h_in=float(m.group(4)))


def compressed_state(run):
    """A run's compression: steps, w at F_v (mm), target F_v and the mean F_v while shearing (N)."""
    d = read_csv(Path(run) / "shear.csv")
    dt = shear_timestep(run)
    target = float(_search(COMPRESSED_LINE, Path(run) / "log.shear", "COMPRESSED").group(2))
    shearing = d["u_mm"] > 0
    return dict(steps=int(round(d["time_s"][0] / dt)), w=float(d["w_mm"][0]), target=target,
                Fv=float(d["Fv_N"][shearing].mean()), csv=d)


def variants(root, fill=None):
    """[(label, k or None, [run folders by realization])]: ROOT's V<k> by k, then OTHER's slowest."""
    found = {}
    for r in realizations(root):
        for f in r.glob("V*"):
            if re.fullmatch(r"V\d+", f.name) and (f / "shear.csv").is_file():
                found.setdefault(int(f.name[1:]), []).append(f)
    if not found:
        fail("protocol: %s holds no approach folders V<k> with a shear.csv" % root)
    out = [("approach %d mm/s" % k, k, fs) for k, fs in sorted(found.items())]    # fs by realization
    if fill is not None:
        name = "V%d" % min(found)
        runs = [r / name for r in realizations(fill) if (r / name / "shear.csv").is_file()]
        if not runs:
            fail("protocol: %s holds no %s runs to compare its fill with" % (fill, name))
        out.append(("short fill", None, runs))
    return out


def _sd(x):
    return float(np.std(x, ddof=1)) if len(x) > 1 else float("nan")


def study(root, fill=None):
    """(rows, chosen k or None, fill rows): each variant against the reference."""
    groups = variants(root, fill)
    states = {label: [compressed_state(r) for r in runs] for label, _, runs in groups}
    ref_label = groups[0][0]
    ref = states[ref_label]
    ref_curves = mean_curves([s["csv"] for s in ref])
    fills = [fill_state(r.parent) for r in groups[0][2]]
    n = min(len(runs) for _, _, runs in groups)
    rows, chosen, ok_so_far = [], groups[0][1], True
    for label, k, runs in groups:
        st = states[label]
        w = np.array([s["w"] for s in st])
        dw = w[:n] - np.array([s["w"] for s in ref[:n]])
        de = np.array([(1 + f["e"]) * x / f["h_in"] for f, x in zip(fills, dw)])
        sd_w = float(np.sqrt(0.5 * (_sd(w) ** 2 + _sd([s["w"] for s in ref]) ** 2)))
        fv_dev = max(abs(s["Fv"] / s["target"] - 1) for s in st)
        c = compare(mean_curves([s["csv"] for s in st]), ref_curves, U_FROM)
        passed = None
        if n > 1 and label != ref_label:
            passed = bool(abs(dw.mean()) <= sd_w and all(d <= s for d, s in c.values()) and fv_dev <= FV_TOL)
            if k is not None:
                ok_so_far = ok_so_far and passed
                chosen = k if ok_so_far else chosen
        rows.append(dict(label=label, k=k, n=len(runs), steps=float(np.mean([s["steps"] for s in st])),
                         w=float(w.mean()), sd_w=_sd(w), dw=float(dw.mean()), sd_dw=_sd(dw), sd_w_pooled=sd_w,
                         de=float(de.mean()), fv_dev=fv_dev, dS=c["S_N"][0], sS=c["S_N"][1],
                         dwu=c["w_mm"][0], swu=c["w_mm"][1], passed=passed))
    fill_rows = []
    if fill is not None:
        other = [fill_state(r.parent) for r in groups[-1][2]]
        for key in ("settle", "e", "coordination"):
            a, b = np.array([f[key] for f in fills[:n]], float), np.array([f[key] for f in other[:n]], float)
            fill_rows.append(dict(key=key, ref=float(a.mean()), short=float(b.mean()), diff=float((b - a).mean()),
                                  sd=float(np.sqrt(0.5 * (_sd(a) ** 2 + _sd(b) ** 2)))))
    return rows, (chosen if n > 1 else None), fill_rows


def report(root, fill=None):
    rows, chosen, fill_rows = study(root, fill)
    n = min(r["n"] for r in rows)
    lines = ["# Protocol study: %s (%d realization%s per variant)" % (root, n, "" if n == 1 else "s"), "",
             "Each variant against %s: w at F_v (mean of the fills, sd between them; the paired difference "
             "from the same fill's reference run, also as a void ratio), F_v held while shearing, and the "
             "S-u and w-u curves from u = %g mm (rms difference of the means, the fills' pooled sd). A "
             "variant passes when each difference is within its spread and F_v within %.1f %%."
             % (rows[0]["label"], U_FROM, 100 * FV_TOL), "",
             "| variant | runs | compression steps | w at F_v (mm) | dw paired (mm) | sd of w between fills (mm) "
             "| de | F_v: largest deviation | S: rms diff / spread (N) | w-u: rms diff / spread (mm) | passes |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append("| %s | %d | %.0f | %.4f +- %.4f | %+.4f +- %.4f | %.4f | %+.5f | %.3f %% | %.1f / %.1f | %.4f / %.4f | %s |" % (
            r["label"], r["n"], r["steps"], r["w"], r["sd_w"], r["dw"], r["sd_dw"], r["sd_w_pooled"], r["de"],
            100 * r["fv_dev"], r["dS"], r["sS"], r["dwu"], r["swu"],
            "reference" if r is rows[0] else {True: "yes", False: "no", None: "n/a"}[r["passed"]]))
    lines.append("")
    if fill_rows:
        lines += ["The fills (each realization's default settling against the short one, same seed):", "",
                  "| | default | short | mean difference | sd between fills |", "|---|---|---|---|---|"]
        lines += ["| %s | %.4g | %.4g | %+.4g | %.4g |" % (f["key"], f["ref"], f["short"], f["diff"], f["sd"])
                  for f in fill_rows]
        lines.append("")
    if chosen is None:
        lines.append("One realization: no spread to judge by; run with --realizations 3.")
    else:
        lines.append("Chosen: an approach at %d mm/s, the fastest whose slower ones all pass." % chosen)
    text = "\n".join(lines) + "\n"
    (Path(root) / "protocol.md").write_text(text)
    keys = ["label", "k", "n", "steps", "w", "sd_w", "dw", "sd_dw", "sd_w_pooled", "de", "fv_dev",
            "dS", "sS", "dwu", "swu", "passed"]
    with open(Path(root) / "protocol.csv", "w") as f:
        f.write(",".join(keys) + "\n")
        for r in rows:
            f.write(",".join("%.6g" % r[k] if isinstance(r[k], float) else str(r[k]) for k in keys) + "\n")
    return text, chosen


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if len(argv) not in (1, 3) or (len(argv) == 3 and argv[1] != "--fill"):
        print(__doc__.strip())
        return 2
    text, _ = report(argv[0], argv[2] if len(argv) == 3 else None)
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
