"""A stack of bags with film sheets between them, cycled (inputs/in.cyclic -var bags N): the split
of the top plate's displacement into the bags' shear and the slip across each film, the slip
fraction against the amplitude, and each film interface's own loop.

A stack run is a cyclic run (cyclic.csv, read by cyclic.CyclicRun: its loops, K_eq, h_eq and R-O
fit are the cyclic analysis's) plus stack.txt: fix ave/time rows over the same steps as
cyclic.csv's rows, with per bag k the mean x displacement of its bottom and top face of yarn
particles (c_botK, c_topK, m) and per film k its x displacement (f_filmK[4], m), the x forces on
it from the bag above and below (f_filmK[14], f_filmK[17], N; the film interface's force is
the one from the bag above) and its height (f_filmK[11], m).
Amplitudes are half the peak-to-peak range over a cycle. Slip across film k is the bag above's
bottom face minus the bag below's top face (below the film: film - top face; above it: bottom
face - film); the slip fraction is the sum of the films' slip amplitudes over the plate's.
"""
import csv
import functools
import re
import sys
from pathlib import Path

import numpy as np

from tbagspost import cyclic, fail, hysteresis, style

HEADER = re.compile(r"^#\s*TimeStep\s+(.*)$", re.M)
LOG_FILMS = re.compile(r"^FILMS: (\d+) between (\d+) bags, friction (\S+) above and (\S+) below", re.M)


def column_name(name):
    """stack.txt's LAMMPS names as ours: v_t -> t, c_top2 -> top2, f_film1[4] -> film1_x ..."""
    m = re.fullmatch(r"f_(film\d+)\[(\d+)\]", name)
    if m:
        return m.group(1) + {"4": "_x", "14": "_Fabove", "17": "_Fbelow", "11": "_z",
                             "16": "_Nabove"}[m.group(2)]
    return re.sub(r"^[vc]_", "", name)


def read_stack(path):
    """stack.txt as {column: array}, one row per step (a resumed run's rows replace the ones
    it wrote again); stops clearly if missing or malformed."""
    path = Path(path)
    if not path.is_file():
        fail("no %s (a stack run of inputs/in.cyclic with -var bags N writes it)" % path)
    text = path.read_text()
    header = HEADER.findall(text)
    if not header:
        fail("%s has no '# TimeStep ...' header (not fix ave/time output?)" % path)
    names = ["step"] + [column_name(n) for n in header[-1].split()]
    try:
        data = np.atleast_2d(np.loadtxt(path, comments="#"))
    except ValueError as e:
        fail("%s is malformed or truncated: %s" % (path, str(e).splitlines()[0]))
    if data.size == 0 or data.shape[1] != len(names):
        fail("%s: expected %d columns (%s)" % (path, len(names), " ".join(names)))
    _, last = np.unique(data[::-1, 0], return_index=True)
    data = data[::-1][last]                      # the last row written for each step, in order
    return {n: data[:, k] for k, n in enumerate(names)}


class StackRun(cyclic.CyclicRun):
    """A cyclic run of a stack: cyclic.csv's rows with stack.txt's beside them (same order)."""

    def __init__(self, path):
        super().__init__(path)
        raw = read_stack(self.path / "stack.txt")
        self.bags = sum(1 for n in raw if re.fullmatch(r"top\d+", n))
        if self.bags < 2:
            fail("%s/stack.txt has %d bag(s): not a stack" % (self.path, self.bags))
        # each cyclic.csv row has the stack.txt row of the same steps (the same mean time)
        t = raw["t"]
        k = np.clip(np.searchsorted(t, self.csv["time_s"]), 1, len(t) - 1)
        k = np.where(np.abs(t[k - 1] - self.csv["time_s"]) < np.abs(t[k] - self.csv["time_s"]), k - 1, k)
        ok = np.abs(t[k] - self.csv["time_s"]) < 1e-6 * np.maximum(1.0, np.abs(t[k]))
        if not ok.all():
            fail("%s: %d rows of cyclic.csv have no stack.txt row" % (self.path, (~ok).sum()))
        self.stack = {n: v[k] for n, v in raw.items()}
        films = LOG_FILMS.search(self.log)
        self.film_mu = (float(films.group(3)), float(films.group(4))) if films else None

    @functools.cached_property
    def split(self):
        """split_table(self), computed once (the stack's report and its isolator model read it)."""
        return split_table(self)

    @property
    def label(self):
        mu = " (film $\\mu$ %g)" % self.film_mu[0] if self.film_mu else ""
        return "$F_v$ = %.0f N, %d bags%s" % (self.fv_N, self.bags, mu)

    @property
    def short(self):
        return "%.0f, %d bags" % (self.fv_N, self.bags)

    def parts(self, rows):
        """The displacement parts (mm) over some rows of cyclic.csv: plate u; per bag its shear;
        per film the slip below, above and across it; the slips at the plates."""
        idx = np.searchsorted(self.csv["time_s"], rows["time_s"])
        s = {n: v[idx] for n, v in self.stack.items()}
        mm = lambda n: 1000 * s[n]  # noqa: E731
        out = {"u": rows["u_mm"], "plate_bottom": mm("bot1"),
               "plate_top": rows["u_mm"] - mm("top%d" % self.bags)}
        for b in range(1, self.bags + 1):
            out["bag%d" % b] = mm("top%d" % b) - mm("bot%d" % b)
        for f in range(1, self.bags):
            out["film%d_below" % f] = mm("film%d_x" % f) - mm("top%d" % f)
            out["film%d_above" % f] = mm("bot%d" % (f + 1)) - mm("film%d_x" % f)
            out["film%d" % f] = mm("bot%d" % (f + 1)) - mm("top%d" % f)
            out["film%d_force" % f] = s["film%d_Fabove" % f]    # of the bag above on the film, N
            out["film%d_z" % f] = mm("film%d_z" % f)
            if "film%d_Nabove" % f in s:      # the normal force through the film (N)
                out["film%d_normal" % f] = -s["film%d_Nabove" % f]
        return out


def amplitude(x):
    return 0.5 * float(np.max(x) - np.min(x))


def split_table(run):
    """Per complete cycle: the amplitude of every part (mm), the slip and bag fractions of the
    plate's amplitude, each film interface's force amplitude, its friction mobilised (force over
    the normal force through the film: F_v and the weight of the bags above, from stack.txt's
    film z force; a run that did not record it (before 2026-12-05) gets F_v, and is told so) and
    its loop's K_eq and h_eq."""
    if "film1_Nabove" not in run.stack:
        print("tbagspost: %s: stack.txt has no film normal force (a run before 2026-12-05): the "
              "mobilised friction is over F_v alone, high by the weight of the bags above the film "
              "(about 2 %% per demo bag at 216 N)" % run.name, file=sys.stderr)
    out = []
    for amp, cyc, rows in run.cycles():
        p = run.parts(rows)
        ua = amplitude(p["u"])
        t = dict(amp=amp, cycle=cyc, ua_nominal_mm=float(rows["ua_mm"][0]), ua_mm=ua,
                 Fv_mean_N=float(rows["Fv_N"].mean()))
        for name in p:
            if not name.endswith(("_force", "_z", "_normal")):
                t[name + "_mm"] = amplitude(p[name])
        films = range(1, run.bags)
        t["slip_fraction"] = sum(t["film%d_mm" % f] for f in films) / ua
        t["bag_fraction"] = sum(t["bag%d_mm" % b] for b in range(1, run.bags + 1)) / ua
        for f in films:
            force = p["film%d_force" % f]
            t["film%d_force_N" % f] = amplitude(force)
            normal = p.get("film%d_normal" % f)
            t["film%d_normal_N" % f] = float(np.mean(normal)) if normal is not None else float("nan")
            t["film%d_mobilised" % f] = amplitude(force) / (
                t["film%d_normal_N" % f] if normal is not None else t["Fv_mean_N"])
            m = cyclic.loop(run, amp, cyc, p["film%d" % f], force)
            t["film%d_h_eq" % f] = m.h_eq
            t["film%d_settle_mm" % f] = float(p["film%d_z" % f][-1] - p["film%d_z" % f][0])
        out.append(t)
    return out


def figure(run, tab):
    """(a) the slip fraction against u_a (first and last cycle); (b) the amplitude of each part
    against u_a (last cycle); (c) each film's loop, the force of the bag above on the film
    against the slip across it (last cycle of each amplitude)."""
    fig, (aa, ab, ac) = style.figure(1, 3, width=9.0, height=2.8)
    first = min(t["cycle"] for t in tab)
    last = max(t["cycle"] for t in tab)
    amps = sorted({t["ua_nominal_mm"] for t in tab})
    for cyc, mark, ls in ((last, "o", "-"), (first, "s", ":")):
        rows = [t for t in tab if t["cycle"] == cyc]
        aa.plot([t["ua_mm"] for t in rows], [t["slip_fraction"] for t in rows], marker=mark, ls=ls,
                color="k", mfc="none" if cyc == first else None, ms=4, label="cycle %d" % cyc)
    lastrows = [t for t in tab if t["cycle"] == last]
    ua = [t["ua_mm"] for t in lastrows]
    parts = ["bag%d" % b for b in range(1, run.bags + 1)] + ["film%d" % f for f in range(1, run.bags)]
    for i, name in enumerate(parts + ["plate_bottom", "plate_top"]):
        ab.plot(ua, [max(t[name + "_mm"], 1e-5) for t in lastrows], marker="o", ms=3,
                ls="-" if name in parts else ":", color=cyclic.load_color(i),
                label=name.replace("_", " ").replace("film", "slip across film ").replace("bag", "shear of bag "))
    ab.plot(ua, ua, color="0.6", lw=0.6, label="plate $u_a$")
    for amp, rows in cyclic.last_cycles(run).items():
        p = run.parts(rows)
        for f in range(1, run.bags):
            ac.plot(p["film%d" % f], p["film%d_force" % f] / 1000, lw=0.8,
                    label="$u_a$ = %g mm" % rows["ua_mm"][0] if f == 1 else None)
    for ax in (aa, ab):
        cyclic.amplitude_axis(ax, amps)
    ab.set_yscale("log")
    aa.set_ylim(0, 1.05)
    aa.set_ylabel("slip fraction (films / plate)")
    ab.set_ylabel("amplitude (mm)")
    ac.set_xlabel("slip across the film (mm)")
    ac.set_ylabel("film force from above (kN)")
    aa.legend(frameon=False, fontsize=6, loc="lower right")
    ab.legend(frameon=False, fontsize=5)
    ac.legend(frameon=False, fontsize=5)
    for ax, lab in ((aa, "(a)"), (ab, "(b)"), (ac, "(c)")):
        style.panel_label(ax, lab)
    fig.tight_layout()
    return fig


def report(run, tab):
    """The stack section of report.md."""
    films = range(1, run.bags)
    mu = ("film friction %g above, %g below" % run.film_mu) if run.film_mu else "film friction: see the log"
    lines = ["", "## Stack: %d bags, %s (%s)" % (run.bags, mu, run.path.name), "",
             "Amplitudes (half peak-to-peak) of the parts of the top plate's displacement; slip "
             "fraction = the films' slip over the plate's amplitude; mobilised = the force through "
             "the film over %s; h_eq of the film interface's own loop (the force of the bag above on "
             "the film against the slip across it)." % (
                 "the normal force through it (F_v and the weight above)" if "film1_Nabove" in run.stack
                 else "F_v (this run did not record the film's normal force: high by the weight "
                      "above the film)"), "",
             "| u_a (mm) | cycle | slip fraction | bag shear (mm) | film slip (mm) | plate slips bottom/top (mm) | "
             "mobilised | film h_eq |", "|---|---|---|---|---|---|---|---|"]
    for t in tab:
        lines.append("| %g | %d | %.3f | %s | %s | %.4f / %.4f | %s | %s |" % (
            t["ua_nominal_mm"], t["cycle"], t["slip_fraction"],
            " + ".join("%.4f" % t["bag%d_mm" % b] for b in range(1, run.bags + 1)),
            " + ".join("%.4f" % t["film%d_mm" % f] for f in films),
            t["plate_bottom_mm"], t["plate_top_mm"],
            ", ".join("%.4f" % t["film%d_mobilised" % f] for f in films),
            ", ".join("%.3f" % t["film%d_h_eq" % f] for f in films)))
    return "\n".join(lines) + "\n"


def write(run, out, formats=("png",), dpi=None):
    """stack-split figure, stack_split.csv; returns the written paths and the report section."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    tab = run.split
    if not tab:
        fail("%s: no complete cycle" % run.path)
    written = style.save(figure(run, tab), out / ("stack-split-%s" % run.name), formats, dpi)
    path = out / ("stack_split-%s.csv" % run.name)
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        keys = list(tab[0].keys())
        w.writerow(keys)
        for t in tab:
            w.writerow(["%.6g" % t[k] for k in keys])
    return written + [path], report(run, tab)
