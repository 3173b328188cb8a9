"""The figure: stress ratio and volumetric strain against axial strain, data and fits."""
from .common import PAPER


def label(tag, r):
    """'paper: ...' for a start at the paper's set, else 'start: ...'; 'fitted: ...' for the best."""
    name = "fitted" if tag == "best" else "paper" if all(r[k] == PAPER[k] for k in PAPER) else "start"
    return "%s: mu %.3g, mu_r %.3g, E %.3g GPa" % (name, r["mu"], r["mur"], r["E"] / 1e9)


def figure(path, data, curves, ps, paper, best):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(2, len(ps), figsize=(4.2 * len(ps), 7), squeeze=False, sharex="col")
    for k, p in enumerate(ps):
        d = data[p][1]
        ax[0, k].plot(d[:, 0], d[:, 1], "ko", ms=3, label="Toyoura e0 0.68 (%s)" % data[p][0])
        ax[1, k].plot(d[:, 0], d[:, 2], "ko", ms=3)
        for tag, r, sty in (("start", paper, "C0--"), ("best", best, "C3-")):
            c = curves[(tag, p)]
            ax[0, k].plot(c["eps_a_pct"], c["ratio"], sty, label=label(tag, r))
            ax[1, k].plot(c["eps_a_pct"], c["eps_v_pct"], sty)
        ax[0, k].set_title("sigma3 = %g MPa" % p)
        ax[0, k].set_ylabel("sigma1 / sigma3")
        ax[1, k].set_ylabel("volumetric strain (%, contraction +)")
        ax[1, k].set_xlabel("axial strain (%)")
        ax[0, k].legend(fontsize=7)
        ax[1, k].axhline(0, color="0.7", lw=0.5)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
