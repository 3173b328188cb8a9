"""The bracket (fit.py --bracket DIR,DIR,...): the paper's sand under each reading of its
conventions, one report directory per reading (fit.py --budget 1 with the options of the
reading), tabulated against the data: misfit, peak stress ratio, largest contraction and
volumetric strain at 10 % axial strain, each the samples' mean +- their standard deviation."""
import csv
import json
import math
from pathlib import Path

from .common import fail
from .study import data_measures

OPTIONS = "options.json"


def reading(opts):
    """The reading's name from the options its report was made with."""
    return "%s radius, twisting %s, %s cell" % (opts["rolling_radius"], opts["twisting"], opts["cell"])


def first_row(out_dir):
    path = Path(out_dir) / "runs.csv"
    if not path.is_file() or not (Path(out_dir) / OPTIONS).is_file():
        fail("--bracket %s: no runs.csv and %s there (run fit.py --budget 1 --out %s first)"
             % (out_dir, OPTIONS, out_dir))
    with open(path, newline="") as fh:
        row = next(csv.DictReader(fh))
    return row, json.loads((Path(out_dir) / OPTIONS).read_text())


def write_bracket(dirs, data, out_path):
    """Markdown table of the readings in dirs (the first row of each runs.csv: the start set)."""
    ps = sorted(data)
    dm = {p: data_measures(data[p][1]) for p in ps}
    rows = [first_row(d) for d in dirs]

    def val(row, key, p, fmt_="%.2f"):
        """'mean +- sd' of the column key (its spread: key_sd, peak_sim's: peak_sd)."""
        m, s = row.get(key % p), row.get(key.replace("_sim", "").replace("_%g", "_sd_%g") % p)
        if m in (None, "") or s in (None, ""):
            fail("--bracket: runs.csv has no column %s (made by an older fit.py: rerun it with the "
                 "same --workdir, every run is cached)" % (key % p))
        m, s = float(m), float(s)
        # a spread below the mean's last digit gets one more digit (not "+- 0.00")
        return (fmt_ % m) + ((" +- " + (fmt_ if s >= 0.005 else "%.3f") % s) if s > 0 else "")

    L = ["| reading | seeds | J | peak ratio %s (data %s) | phi at peak, deg (data %s) | largest contraction %% (data %s) "
         "| eps_v at 10 %% axial, %% (data %s; - dilation) |" % (
             " / ".join("%g" % p for p in ps), " / ".join("%.2f" % dm[p]["peak"] for p in ps),
             " / ".join("%.1f" % phi(dm[p]["peak"]) for p in ps),
             " / ".join("%.2f" % dm[p]["contraction"] for p in ps),
             " / ".join("%.2f" % dm[p]["ev_10"] for p in ps)), "|---" * 7 + "|"]
    for row, opts in rows:
        L.append("| %s | %d | %.3f | %s | %s | %s | %s |" % (
            reading(opts), len(opts["seeds"]), float(row["J"]),
            " / ".join(val(row, "peak_sim_%g", p) for p in ps),
            " / ".join("%.1f" % phi(float(row["peak_sim_%g" % p])) for p in ps),
            " / ".join(val(row, "contraction_%g", p) for p in ps),
            " / ".join(val(row, "ev10_%g", p) for p in ps)))
    text = "\n".join(L) + "\n"
    Path(out_path).parent.mkdir(parents=True, exist_ok=True)
    Path(out_path).write_text(text)
    return text


def phi(ratio):
    """Mobilised friction angle (deg) of a triaxial stress ratio sigma1/sigma3."""
    return math.degrees(math.asin((ratio - 1.0) / (ratio + 1.0)))
