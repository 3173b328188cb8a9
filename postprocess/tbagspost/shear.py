"""S-u and w-u of shear runs (the paper's Part 2, Fig. 3): shear force S in kN and vertical
displacement w in mm against the horizontal displacement u in mm, one curve per run, labelled
with its F_v. w is counted from the start of shearing (w < 0: contraction, the top plate moved
down; > 0: dilatancy). The curves are the CSV's means over each output interval; where the CSV
has the interval's min and max (S_min_N, S_max_N, w_min_mm, w_max_mm), a light band shows them."""
import numpy as np

from tbagspost import bounds, style


def speed_mm_s(run):
    """The shear speed of a run (mm/s): the median of du/dt over its CSV rows."""
    d = run.csv
    dt = np.diff(d["time_s"])
    ok = dt > 0
    return float(np.median(np.diff(d["u_mm"])[ok] / dt[ok])) if ok.any() else float("nan")


def labels(runs):
    """Each run's legend label: its F_v, and what else differs where F_v is the same (the shear
    speed, else the run's folder)."""
    out = [run.label for run in runs]
    if len(set(out)) == len(out):
        return out
    out = ["%s, $v$ = %.3g mm/s" % (run.label, speed_mm_s(run)) for run in runs]
    if len(set(out)) == len(out):
        return out
    return ["%s (%s)" % (run.label, run.name) for run in runs]


def figure(runs, title=None):
    """Figure with S-u (left) and w-u (right) of the runs (tbagspost.run.Run); returns
    (Figure, stats) where stats has per run: peak S (kN) and its u, F_v, min and final w."""
    fig, (a_s, a_w) = style.figure(1, 2, width=7.0, height=2.8)
    stats = []
    band = False
    for run, label in zip(runs, labels(runs)):
        d = run.csv
        u, s, w = d["u_mm"], d["S_N"] / 1000, d["w_mm"] - d["w_mm"][0]
        line, = a_s.plot(u, s, label=label)
        a_w.plot(u, w, label=label, color=line.get_color(), linestyle=line.get_linestyle())
        names = d.dtype.names
        band = band or "S_min_N" in names
        if "S_min_N" in names and "S_max_N" in names:
            a_s.fill_between(u, d["S_min_N"] / 1000, d["S_max_N"] / 1000, color=line.get_color(),
                             alpha=0.15, lw=0)
        if "w_min_mm" in names and "w_max_mm" in names:
            a_w.fill_between(u, d["w_min_mm"] - d["w_mm"][0], d["w_max_mm"] - d["w_mm"][0],
                             color=line.get_color(), alpha=0.15, lw=0)
        k = int(np.argmax(s))
        drops = np.diff(s)
        stats.append(dict(run=run.name, **run.model, Fv_kN=run.fv_kN, S_peak_kN=float(s[k]), u_peak_mm=float(u[k]),
                          u_final_mm=float(u[-1]), S_final_kN=float(s[-1]), w_min_mm=float(w.min()),
                          w_final_mm=float(w[-1]), largest_drop_kN=float(max(0.0, -drops.min()))))
    a_s.set_xlabel("horizontal displacement $u$ (mm)")
    a_s.set_ylabel("shear force $S$ (kN)")
    a_w.set_xlabel("horizontal displacement $u$ (mm)")
    a_w.set_ylabel("vertical displacement $w$ (mm)")
    a_w.axhline(0, color="0.5", lw=0.6)
    for ax, tag in ((a_s, "(a)"), (a_w, "(b)")):
        ax.set_xlim(left=0)
        handles, texts = ax.get_legend_handles_labels()
        if band:    # say what the shading is
            from matplotlib.patches import Patch
            handles.append(Patch(color="0.5", alpha=0.3, lw=0))
            texts.append("min-max within each output interval")
        ax.legend(handles, texts, loc="lower right" if ax is a_s else "best", frameon=False,
                  fontsize="small" if band else None)
        style.panel_label(ax, tag)
    a_s.set_ylim(bottom=min(0.0, a_s.get_ylim()[0]))
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    return fig, stats


def describe(st):
    """One line of numbers for a run's S-u and w-u."""
    line = ("%s: F_v %.2f kN; peak S %.3f kN at u %.2f mm, S %.3f kN at u %.2f mm; w min %.3f mm, "
            "final %.3f mm (from the start of shear); largest drop of S %.3f kN"
            % (st["run"], st["Fv_kN"], st["S_peak_kN"], st["u_peak_mm"], st["S_final_kN"],
               st["u_final_mm"], st["w_min_mm"], st["w_final_mm"], st["largest_drop_kN"]))
    if "fabric" in st and st["Fv_kN"] > 0:
        line += "; fabric %s, peak %s" % (st["fabric"], bounds.describe(st["S_peak_kN"] / st["Fv_kN"], st["sand"]))
    return line
