"""Drained triaxial runs (calibration/in.triax): stress ratio sigma1/sigma3 and volumetric strain
against axial strain (the paper's Part 1 calibration on Toyoura sand), one curve per run labelled
with its confining pressure sigma3 (median of the lateral stresses sx, sy).

A triaxial run directory holds a CSV whose header starts with eps_a_pct (in.triax's ${csv},
default triax.csv): eps_a_pct, eps_v_pct (contraction > 0), q_Pa, ratio, p_Pa, Z, sx_Pa, sy_Pa, ...
"""
from pathlib import Path

import numpy as np

from tbagspost import fail, read_columns, style

COLUMNS = ("eps_a_pct", "eps_v_pct", "q_Pa", "ratio", "sx_Pa", "sy_Pa")


def find_csv(path):
    """The triaxial CSV of a run directory, or None when it has none."""
    for p in sorted(Path(path).glob("*.csv")):
        with open(p) as f:
            if f.readline().startswith("eps_a_pct"):
                return p
    return None


def read(path):
    """A triaxial CSV as a structured array; stops clearly if it is short or lacks columns."""
    d = read_columns(path, COLUMNS, "calibration/in.triax")
    if len(d) < 2 or np.isnan(d[-1]["ratio"]):
        fail("%s has fewer than two full rows (truncated run?)" % path)
    return d


def sigma3_kPa(d):
    return float(np.median(0.5 * (d["sx_Pa"] + d["sy_Pa"]))) / 1000


def figure(paths):
    """Figure of the triaxial CSVs: (a) sigma1/sigma3 - eps_a, (b) eps_v - eps_a; returns
    (Figure, stats) with per run the peak ratio, its strain, the friction angle at the peak and
    the final volumetric strain."""
    fig, (a_r, a_v) = style.figure(1, 2, width=7.0, height=2.8)
    stats = []
    for path in paths:
        d = read(path)
        label = "$\\sigma_3$ = %.0f kPa" % sigma3_kPa(d)
        a_r.plot(d["eps_a_pct"], d["ratio"], label=label)
        a_v.plot(d["eps_a_pct"], d["eps_v_pct"], label=label)
        k = int(np.argmax(d["ratio"]))
        r = float(d["ratio"][k])
        stats.append(dict(run=Path(path).parent.name, sigma3_kPa=sigma3_kPa(d), ratio_peak=r,
                          eps_a_peak_pct=float(d["eps_a_pct"][k]),
                          phi_peak_deg=float(np.degrees(np.arcsin((r - 1) / (r + 1)))),
                          eps_v_final_pct=float(d["eps_v_pct"][-1])))
    a_r.set_xlabel("axial strain $\\varepsilon_a$ (%)")
    a_r.set_ylabel("stress ratio $\\sigma_1/\\sigma_3$")
    a_v.set_xlabel("axial strain $\\varepsilon_a$ (%)")
    a_v.set_ylabel("volumetric strain $\\varepsilon_v$ (%), contraction > 0")
    a_v.axhline(0, color="0.5", lw=0.6)
    for ax, tag in ((a_r, "(a)"), (a_v, "(b)")):
        ax.set_xlim(left=0)
        ax.legend(frameon=False)
        style.panel_label(ax, tag)
    fig.tight_layout()
    return fig, stats


def describe(st):
    return ("%s: sigma3 %.0f kPa; peak sigma1/sigma3 %.3f at eps_a %.2f %% (friction angle %.1f deg); "
            "final eps_v %.3f %%" % (st["run"], st["sigma3_kPa"], st["ratio_peak"], st["eps_a_peak_pct"],
                                     st["phi_peak_deg"], st["eps_v_final_pct"]))
