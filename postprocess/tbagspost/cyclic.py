"""Cyclic simple shear runs (inputs/in.cyclic): the loops of every cycle, K_eq and h_eq against the
amplitude, the Ramberg-Osgood fit per load, and a report a designer can paste into a design note.

A run directory holds cyclic.csv (rows of the means over each row's steps, with the amplitude and
cycle indices) and its log (log.cyclic or screen.cyclic.txt, for the conditions). Rows of an
interrupted amplitude that a resumed run wrote again are dropped (the later ones are kept).
The R-O model is fitted to the last cycle of each amplitude (its tips and its loop points; the
first cycle starts on the virgin backbone, not on a Masing branch). Definitions: hysteresis.py.
"""
import csv
import re
import sys
from pathlib import Path

import numpy as np

from tbagspost import fail, finite_rows, hysteresis, read_columns, style, superseded

COLUMNS = ("time_s", "amp", "cycle", "ua_mm", "u_mm", "w_mm", "S_N", "Fv_N")
LOG_AMP = re.compile(r"^AMPLITUDE (\d+) of \d+: u_a (\S+) mm, f (\S+) Hz .*peak speed (\S+) mm/s, "
                     r"inertial number at peak (\S+)", re.M)
LOG_CYCLIC = re.compile(r"^CYCLIC: (.*)$", re.M)
LOG_SAND = re.compile(r"^SAND: (.*)$", re.M)
LOG_DT = re.compile(r"^TIMESTEP:.*using\s+(\S+)\s+s", re.M)


LOG_ROWS = re.compile(r"^# amplitude (\d+): u_a \S+ mm, \d+ cycles of (\d+) steps, rows of (\d+) steps", re.M)


def read_csv(path):
    """cyclic.csv as a structured array, rows in time order without the rows a resumed run
    superseded; stops clearly if missing, malformed or empty, or on a non-finite value (naming
    the row; only the file's last row may be cut short, by an interrupted run, and is dropped)."""
    d = finite_rows(read_columns(path, COLUMNS, "inputs/in.cyclic"), COLUMNS, path,
                    lambda d, k: "time %g s, amplitude %g, cycle %g" % (d["time_s"][k], d["amp"][k], d["cycle"][k]))
    if len(d) < 2:
        fail("%s has fewer than two rows (truncated run?)" % path)
    # a resumed run restarts the time: keep a row only if every later row is later in time
    return d[~superseded(d["time_s"])]


def rows_per_cycle(path):
    """{amplitude: rows per cycle} from cyclic.csv's '# amplitude' lines (the deck's period over
    its row length); {} for a file without them."""
    text = Path(path).read_text(errors="replace")
    return {int(a): int(period) // int(row) for a, period, row in LOG_ROWS.findall(text)}


LOG_FABRIC = re.compile(r"^FABRIC: (\w+):", re.M)


class RowsRun:
    """What a run of rows under a held F_v has (cyclic and history runs): its folder's name, its
    F_v (the median of the rows'), its log and the bag's fabric."""

    def read_log(self):
        self.log = ""
        for p in sorted(self.path.glob("log.cyclic")) + sorted(self.path.glob("screen.cyclic*")):
            self.log = p.read_text(errors="replace")
            break

    @property
    def fabric(self):
        """The fabric its log names (inputs/fabric.lmp); runs from before the fabric choice
        (no FABRIC line) had the solid bond."""
        m = LOG_FABRIC.search(self.log)
        return m.group(1) if m else "solid"

    @property
    def name(self):
        return self.path.resolve().name

    @property
    def fv_N(self):
        return float(np.median(self.csv["Fv_N"]))


class CyclicRun(RowsRun):
    """A cyclic run directory: its rows, cycles and conditions."""

    def __init__(self, path):
        self.path = Path(path)
        self.csv = read_csv(self.path / "cyclic.csv")
        self.row_counts = rows_per_cycle(self.path / "cyclic.csv")
        self._cycles = None
        self.read_log()

    @property
    def label(self):
        return "$F_v$ = %.0f N" % self.fv_N

    @property
    def short(self):
        """The run in a table's first column."""
        return "%.0f" % self.fv_N

    def rows_per_cycle(self, amp):
        """The deck's rows per cycle at an amplitude: from cyclic.csv's '# amplitude' lines, else
        the most common count of that amplitude's cycles."""
        if amp in self.row_counts:
            return self.row_counts[amp]
        keys = self.keys()
        _, counts = np.unique(keys[keys[:, 0] == amp], axis=0, return_counts=True)
        return int(np.bincount(counts).argmax())

    def keys(self):
        return np.stack([self.csv["amp"], self.csv["cycle"]], axis=1).astype(int)

    def cycles(self):
        """The complete cycles, in order: list of (amp, cycle, rows) (found once; the figures
        and tables ask for them many times). Stops when a cycle is missing (each amplitude's
        cycles are 1, 2, ...) or has other than the deck's rows per cycle, except the last
        cycle of the file, which an interrupted run leaves short: it is left out, and said."""
        if self._cycles is None:
            keys = self.keys()
            order = list(dict.fromkeys(map(tuple, keys)))
            self._cycles = []
            for k, (amp, cyc) in enumerate(order):
                rows = self.csv[(keys[:, 0] == amp) & (keys[:, 1] == cyc)]
                expected = (order[k - 1][1] + 1) if k and order[k - 1][0] == amp else 1
                if cyc != expected:
                    fail("%s: amplitude %d has no cycle %d (rows missing from cyclic.csv?); its "
                         "next cycle is %d" % (self.path / "cyclic.csv", amp, expected, cyc))
                n = self.rows_per_cycle(amp)
                if len(rows) == n:
                    self._cycles.append((amp, cyc, rows))
                elif k == len(order) - 1 and len(rows) < n:
                    print("tbagspost: %s: amplitude %d, cycle %d has %d of its %d rows (the run "
                          "stopped in it): left out" % (self.path.name, amp, cyc, len(rows), n),
                          file=sys.stderr)
                else:
                    fail("%s: amplitude %d, cycle %d has %d rows, the deck writes %d per cycle"
                         % (self.path / "cyclic.csv", amp, cyc, len(rows), n))
        return self._cycles

    def conditions(self):
        """Per amplitude index: (u_a mm, f Hz, peak speed mm/s, inertial number at peak) from
        the log; also the CYCLIC, SAND and TIMESTEP lines."""
        amps = {int(m[0]): tuple(float(x) for x in m[1:]) for m in LOG_AMP.findall(self.log)}
        get = lambda rx: (rx.search(self.log).group(1) if rx.search(self.log) else "")  # noqa: E731
        return dict(amps=amps, cyclic=get(LOG_CYCLIC), sand=get(LOG_SAND), dt=get(LOG_DT))


def table(run):
    """One dict per complete cycle: amp, cycle, u_a (nominal and measured), K_eq, W_d, h_eq,
    S_a, and w at the cycle's end (mm, counted from the start of cycling)."""
    w0 = run.csv["w_mm"][0]
    out = []
    for amp, cyc, rows in run.cycles():
        m = loop(run, amp, cyc, rows["u_mm"], rows["S_N"])
        out.append(dict(amp=amp, cycle=cyc, ua_nominal_mm=float(rows["ua_mm"][0]), ua_mm=m.u_a,
                        S_a_N=m.S_a, K_eq_N_per_mm=m.K_eq, W_d_J=m.W_d / 1000, h_eq=m.h_eq,
                        Fv_mean_N=float(rows["Fv_N"].mean()),
                        w_end_mm=float(rows["w_mm"][-1] - w0)))
    return out


def loop(run, amp, cyc, u, S):
    """hysteresis.measure of one cycle (one period of the drive); a loop it refuses stops with a
    line naming the cycle."""
    try:
        return hysteresis.measure(u, S, one_period=True)
    except ValueError as e:
        fail("%s: amplitude %d, cycle %d: %s" % (run.path / "cyclic.csv", amp, cyc, e))


def small_strain_stiffness(tab):
    """K_0 of the K_eq/K_0 curves: the secant stiffness of the last cycle at the smallest
    amplitude (measured, as G_0 from the smallest strain level of a cyclic soil test)."""
    smallest = min(t["ua_nominal_mm"] for t in tab)
    return [t for t in tab if t["ua_nominal_mm"] == smallest][-1]["K_eq_N_per_mm"]


def last_cycles(run):
    """The last complete cycle of each amplitude: {amp: rows}."""
    last = {}
    for amp, _, rows in run.cycles():
        last[amp] = rows
    return last


def fit(run):
    """The R-O fit (hysteresis.Fit, u in mm and S in N) to the last cycle of each amplitude."""
    loops = [(r["u_mm"], r["S_N"]) for r in last_cycles(run).values()]
    if len(loops) < 2:
        fail("%s: the R-O fit needs at least two amplitudes with a complete cycle" % run.path)
    return hysteresis.fit(loops)


def compare(run_a, run_b):
    """K_eq and h_eq of the cycles two runs share (e.g. two frequencies): one dict per
    (amp, cycle) with both values, K_eq's relative and h_eq's absolute difference (b - a)."""
    tb = {(t["amp"], t["cycle"]): t for t in table(run_b)}
    out = []
    for a in table(run_a):
        b = tb.get((a["amp"], a["cycle"]))
        if b is None:
            continue
        out.append(dict(amp=a["amp"], cycle=a["cycle"], ua_mm=a["ua_nominal_mm"],
                        K_a=a["K_eq_N_per_mm"], K_b=b["K_eq_N_per_mm"], h_a=a["h_eq"], h_b=b["h_eq"],
                        dK_rel=b["K_eq_N_per_mm"] / a["K_eq_N_per_mm"] - 1, dh=b["h_eq"] - a["h_eq"]))
    return out


# ---- figures --------------------------------------------------------------------------------
def load_color(i):
    """The colour of the i-th load (the same in every figure)."""
    import matplotlib.pyplot as plt
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    return colors[i % len(colors)]


def amplitude_axis(ax, amps):
    """A log axis of the amplitudes, labelled at the amplitudes themselves."""
    from matplotlib.ticker import NullFormatter
    ax.set_xscale("log")
    ax.set_xticks(amps)
    ax.set_xticklabels(["%g" % a for a in amps])
    ax.xaxis.set_minor_formatter(NullFormatter())
    ax.set_xlabel("amplitude $u_a$ (mm)")


def loops_figure(runs, fits):
    """Loops per load (rows) and amplitude (columns): every cycle (the first lighter), and the
    fitted R-O/Masing loop at the measured amplitude (dashed)."""
    amps = sorted({a for r in runs for a, _, _ in r.cycles()})
    fig, axes = style.figure(len(runs), len(amps), width=1.6 * len(amps) + 0.6,
                             height=1.6 * len(runs) + 0.4, squeeze=False)
    for i, (run, f) in enumerate(zip(runs, fits)):
        ncyc = max(c for _, c, _ in run.cycles())
        for j, amp in enumerate(amps):
            ax = axes[i][j]
            last = None
            for a, c, rows in run.cycles():
                if a != amp:
                    continue
                shade = 0.75 - 0.75 * (c - 1) / max(ncyc - 1, 1)
                ax.plot(rows["u_mm"], rows["S_N"] / 1000, color=str(shade), ls="-", lw=0.8,
                        label="cycle %d" % c if (i, j) == (0, 0) else None)
                last = rows
            if last is not None:
                ua = last["ua_mm"][0]
                S_a = float(f.model.S(hysteresis.measure(last["u_mm"], last["S_N"]).u_a)[0])
                mu, ms = f.model.loop(S_a)
                ax.plot(np.append(mu, mu[0]), np.append(ms, ms[0]) / 1000, "--", color="#d62728", lw=1.0,
                        label="R-O / Masing" if (i, j) == (0, 0) else None)
                ax.set_title("$u_a$ = %g mm" % ua if i == 0 else "")
            if j == 0:
                ax.set_ylabel("%s\n$S$ (kN)" % run.label)
            if i == len(runs) - 1:
                ax.set_xlabel("$u$ (mm)")
    axes[0][0].legend(frameon=False, fontsize=6, loc="upper left")
    fig.tight_layout()
    return fig


def curves_figure(runs, tables, fits):
    """K_eq/K_0 and h_eq against u_a: first and last cycle per load, and the R-O curves (its
    secant stiffness over the same measured K_0)."""
    fig, (ak, ah) = style.figure(1, 2, width=7.0, height=2.8)
    for i, (run, tab, f) in enumerate(zip(runs, tables, fits)):
        k0 = small_strain_stiffness(tab)
        first = min(t["cycle"] for t in tab)
        last = max(t["cycle"] for t in tab)
        color = load_color(i)
        for cyc, mark, ls in ((last, "o", "-"), (first, "s", ":")):
            rows = [t for t in tab if t["cycle"] == cyc]
            ua = np.array([t["ua_mm"] for t in rows])
            ak.plot(ua, [t["K_eq_N_per_mm"] / k0 for t in rows], marker=mark, ls=ls,
                    color=color, mfc="none" if cyc == first else None, ms=4,
                    label="%s, cycle %d" % (run.label, cyc))
            ah.plot(ua, [t["h_eq"] for t in rows], marker=mark, ls=ls, color=color,
                    mfc="none" if cyc == first else None, ms=4)
        grid = np.geomspace(min(t["ua_mm"] for t in tab) / 2, max(t["ua_mm"] for t in tab) * 1.2, 60)
        S = f.model.S(grid)
        ak.plot(grid, S / grid / k0, color=color, ls="-", lw=0.6, alpha=0.6)
        ah.plot(grid, f.model.damping(S), color=color, ls="-", lw=0.6, alpha=0.6)
    amps = sorted({t["ua_nominal_mm"] for tab in tables for t in tab})
    for ax in (ak, ah):
        amplitude_axis(ax, amps)
    ak.set_ylabel("$K_{eq}/K_0$")
    ah.set_ylabel("equivalent damping $h_{eq}$")
    ak.set_ylim(0, 1.15)
    ah.set_ylim(bottom=0)
    ak.legend(frameon=False, fontsize=6)
    style.panel_label(ak, "(a)")
    style.panel_label(ah, "(b)")
    fig.tight_layout()
    return fig


def cycle_position(run):
    """Each row's position in cycles from the start of cycling: the index of its (amp, cycle) in
    order of appearance plus its place within the cycle; and the (amp, cycle) keys in that order."""
    order, first = {}, {}
    x = np.zeros(len(run.csv))
    for k, key in enumerate(map(tuple, run.keys())):
        if key not in order:
            order[key], first[key] = len(order), k
        x[k] = order[key] + (k - first[key] + 0.5) / run.rows_per_cycle(key[0])
    return x, list(order)


def settlement_figure(runs):
    """w against the cycle count (amplitude steps marked): ratcheting settlement."""
    fig, ax = style.figure(1, 1, width=7.0, height=2.6)
    for i, run in enumerate(runs):
        x, _ = cycle_position(run)
        d = run.csv
        ax.plot(x, d["w_mm"] - d["w_mm"][0], label=run.label, color=load_color(i), ls="-")
    _, keys = cycle_position(runs[0])
    ua = dict(zip(map(int, runs[0].csv["amp"]), runs[0].csv["ua_mm"]))
    for k, (amp, cyc) in enumerate(keys):
        if cyc == 1:
            ax.axvline(k, color="0.7", lw=0.5)
            ax.text(k + 0.05, 0.02, "%g mm" % ua[amp], transform=ax.get_xaxis_transform(),
                    fontsize=6, color="0.4")
    ax.set_xlabel("cycle number (amplitude steps marked)")
    ax.set_ylabel("vertical displacement $w$ (mm)")
    ax.legend(frameon=False)
    fig.tight_layout()
    return fig


# ---- tables and report ----------------------------------------------------------------------
def fmt_pm(value, sd, digits=3):
    return "%.*g +- %.2g" % (digits, value, sd)


def report(runs, tables, fits):
    """The Markdown report: conditions, R-O parameters, K_eq and h_eq per load."""
    cond = runs[0].conditions()
    lines = ["# Cyclic simple shear: Ramberg-Osgood parameters, stiffness and damping", "",
             "## Conditions", ""]
    if cond["cyclic"]:
        lines.append("- protocol: %s" % cond["cyclic"])
    if cond["sand"]:
        lines.append("- sand: %s" % cond["sand"])
    if cond["dt"]:
        lines.append("- time step: %s s" % cond["dt"])
    for k, (ua, f, vp, inert) in sorted(cond["amps"].items()):
        lines.append("- amplitude %d: u_a %g mm, %.4g Hz, peak plate speed %.3g mm/s, inertial "
                     "number at peak %.2g (at %.0f N)" % (k, ua, f, vp, inert, runs[0].fv_N))
    lines += ["", "Definitions (JGS 0542/0543, ASTM D8296): K_eq = (S_max - S_min)/(u_max - u_min); "
              "W_d = loop area (trapezoid rule, closed loop); W_e = K_eq u_a^2/2; "
              "h_eq = W_d/(4 pi W_e). R-O backbone u = (S/K_0)(1 + |S/S_y|^(r-1)) (alpha = 1: the "
              "secant stiffness is K_0/2 at S_y), Masing loops, fitted by least squares to the tips "
              "and loop points of the last cycle of each amplitude (residuals in u relative to u_a); "
              "R-O damping h = (2/pi)(r-1)/(r+1)(1 - K_eq/K_0). In the table K_0 is measured: "
              "K_eq of the last cycle at the smallest amplitude (K_0 of the R-O fit is beside it "
              "in the parameters).", "",
              "## Ramberg-Osgood parameters (+- one standard deviation of the fit)", "",
              "| F_v (N) | K_0 (N/mm) | S_y (N) | r | rms error at the tips | rms error along the loops |",
              "|---|---|---|---|---|---|"]
    for run, f in zip(runs, fits):
        m, s = f.model, f.sigma
        lines.append("| %s | %s | %s | %s | %.1f %% | %.1f %% |" % (
            run.short, fmt_pm(m.K0, s.K0), fmt_pm(m.S_y, s.S_y), fmt_pm(m.r, s.r),
            100 * f.rms_backbone, 100 * f.rms_loops))
    lines += ["", "## K_eq and h_eq per amplitude (first and last cycle)", "",
              "| F_v (N) | u_a (mm) | K_eq first (N/mm) | K_eq last (N/mm) | K_eq/K_0 last (measured K_0) | "
              "h_eq first | h_eq last | h R-O | w at the end of the step (mm) |",
              "|---|---|---|---|---|---|---|---|---|"]
    for run, tab, f in zip(runs, tables, fits):
        k0 = small_strain_stiffness(tab)
        for amp in sorted({t["amp"] for t in tab}):
            rows = [t for t in tab if t["amp"] == amp]
            a, b = rows[0], rows[-1]
            h_ro = float(f.model.damping(f.model.S(b["ua_mm"]))[0])
            lines.append("| %s | %g | %.1f | %.1f | %.3f | %.3f | %.3f | %.3f | %.3f |" % (
                run.short, b["ua_nominal_mm"], a["K_eq_N_per_mm"], b["K_eq_N_per_mm"],
                b["K_eq_N_per_mm"] / k0, a["h_eq"], b["h_eq"], h_ro, b["w_end_mm"]))
    return "\n".join(lines) + "\n"


def write(runs, out, formats=("png",), dpi=None):
    """Figures, cyclic_table.csv, ro_parameters.csv and report.md into out; returns the written
    paths and the report."""
    runs = sorted(runs, key=lambda r: -r.fv_N)
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    tables = [table(r) for r in runs]
    fits = [fit(r) for r in runs]
    written = []
    written += style.save(loops_figure(runs, fits), out / "cyclic-loops", formats, dpi)
    written += style.save(curves_figure(runs, tables, fits), out / "cyclic-curves", formats, dpi)
    written += style.save(settlement_figure(runs), out / "cyclic-settlement", formats, dpi)
    with open(out / "cyclic_table.csv", "w", newline="") as fh:
        w = csv.writer(fh)
        keys = list(tables[0][0].keys())
        w.writerow(["run", "Fv_N"] + keys)
        for run, tab in zip(runs, tables):
            for t in tab:
                w.writerow([run.name, "%.2f" % run.fv_N] + ["%.6g" % t[k] for k in keys])
    with open(out / "ro_parameters.csv", "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["run", "Fv_N", "K0_N_per_mm", "K0_sd", "Sy_N", "Sy_sd", "r", "r_sd",
                    "rms_tips", "rms_loops"])
        for run, f in zip(runs, fits):
            m, s = f.model, f.sigma
            w.writerow([run.name, "%.2f" % run.fv_N] + ["%.6g" % v for v in (
                m.K0, s.K0, m.S_y, s.S_y, m.r, s.r, f.rms_backbone, f.rms_loops)])
    text = report(runs, tables, fits)
    (out / "report.md").write_text(text)
    written += [out / "cyclic_table.csv", out / "ro_parameters.csv", out / "report.md"]
    return written, text
