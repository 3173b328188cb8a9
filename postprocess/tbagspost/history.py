"""A displacement history run (inputs/in.cyclic -var history FILE): the DEM's shear force along an
irregular u(t) that no model was fitted to, against each isolator model stepped through the same
u(t): the test of a model a designer would use.

history.csv (in.cyclic's history rows: means over each row's steps) gives time_s, th_s (the
history's time), u_mm, S_N, Fv_N. Per model: the rms of S_model - S_DEM over the rows as a part of
the DEM's largest |S|, and the work done on the isolator over the history, W = integral of S du
(mJ from N and mm; u starts and ends at 0, so W is the energy dissipated but for the elastic
energy left at the end), DEM and model.
"""
from pathlib import Path

import numpy as np

from tbagspost import design, fail, finite_rows, read_columns, rms, style, superseded
from tbagspost.cyclic import RowsRun

COLUMNS = ("time_s", "th_s", "chunk", "u_mm", "S_N", "Fv_N")


class HistoryRun(RowsRun):
    """A history run directory: its rows (a resumed run's rewritten rows dropped)."""

    def __init__(self, path):
        self.path = Path(path)
        f = self.path / "history.csv"
        d = finite_rows(read_columns(f, COLUMNS, "inputs/in.cyclic -var history FILE"), COLUMNS, f,
                        lambda d, k: "history time %g s" % d["th_s"][k])
        self.csv = d[~superseded(d["time_s"])]
        if len(self.csv) < 10:
            fail("%s has %d rows: too few for a history" % (self.path / "history.csv", len(self.csv)))
        self.stack = (self.path / "stack.txt").exists()
        self.read_log()


def work(u, S):
    """Integral of S du along the rows (trapezoid rule), from u = 0 at rest before the first row."""
    u, S = np.r_[0.0, u], np.r_[0.0, S]
    return float(np.sum(0.5 * (S[1:] + S[:-1]) * np.diff(u)))


def compare(run, models):
    """models: [(name, model)]; returns one dict per model (and the DEM's own row first)."""
    u, S = run.csv["u_mm"], run.csv["S_N"]
    peak = float(np.max(np.abs(S)))
    W = work(u, S)
    rows = [dict(run=run.name, fabric=run.fabric, Fv_N=run.fv_N, model="DEM", rms_of_peak=0.0,
                 W_mJ=W, W_ratio=1.0, S_peak_N=peak)]
    for name, model in models:
        Sm = model.simulate(np.r_[0.0, u])[1:]
        Wm = work(u, Sm)
        rows.append(dict(run=run.name, fabric=run.fabric, Fv_N=run.fv_N, model=name,
                         rms_of_peak=rms(Sm - S) / peak,
                         W_mJ=Wm, W_ratio=Wm / W, S_peak_N=float(np.max(np.abs(Sm))), S=Sm))
    return rows


def figure(run, rows):
    """S against the history's time and against u: the DEM and each model."""
    fig, (a, b) = style.figure(1, 2, width=7.0, height=2.8)
    t, u, S = run.csv["th_s"], run.csv["u_mm"], run.csv["S_N"]
    a.plot(t, S, color="k", lw=1.2, label="DEM")
    b.plot(u, S, color="k", lw=1.0, label="DEM")
    for k, r in enumerate(rows[1:]):
        a.plot(t, r["S"], lw=0.7, color="C%d" % k, label=r["model"])
        b.plot(u, r["S"], lw=0.6, color="C%d" % k)
    a.set_xlabel("history time (s)")
    a.set_ylabel("$S$ (N)")
    b.set_xlabel("$u$ (mm)")
    b.set_ylabel("$S$ (N)")
    a.legend(frameon=False, fontsize=6)
    style.panel_label(a, "(a)")
    style.panel_label(b, "(b)")
    fig.tight_layout()
    return fig


def section(run, rows, what):
    lines = ["", "### History %s: %s (%s)" % (run.name, what, "F_v = %.0f N" % run.fv_N), "",
             "%d rows of the history (%.3g s, |u| up to %.2f mm); the models were fitted to the "
             "cyclic runs only. rms: of S_model - S_DEM over the rows, as a part of the DEM's "
             "largest |S| (%.1f N); W: the work integral of S du over the history (energy "
             "dissipated, but for the elastic energy left at the end)." % (
                 len(run.csv), run.csv["th_s"][-1], np.max(np.abs(run.csv["u_mm"])), rows[0]["S_peak_N"]),
             "", "| model | rms of S (of the peak) | W (mJ) | W model / W DEM | largest abs S (N) |",
             "|---|---|---|---|---|"]
    for r in rows:
        lines.append("| %s | %.1f %% | %.1f | %.2f | %.1f |" % (
            r["model"], 100 * r["rms_of_peak"], r["W_mJ"], r["W_ratio"], r["S_peak_N"]))
    return lines



def figure_names(paths):
    """A name per history run folder for its figure: the folder's name, or where two share it the
    shortest tail of their paths that tells them apart, joined by '-' (runs-history/H3730 and
    runs-history-woven/H3730: runs-history-H3730, runs-history-woven-H3730)."""
    parts = [Path(p).resolve().parts for p in paths]
    names = []
    for mine in parts:
        for k in range(1, len(mine) + 1):
            if sum(other[-k:] == mine[-k:] for other in parts) == 1:
                break
        names.append("-".join(mine[-k:]))
    return names


def write_csv(path, rows):
    """history_check.csv: the rows of compare() without the model's S along the history."""
    design.write_csv(path, [{k: v for k, v in r.items() if k != "S"} for r in rows])
