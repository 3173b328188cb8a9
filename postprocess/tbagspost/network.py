"""Contact-force network and bond tension in the central x-z cross-section at one dump step (the
paper's Part 2: contact forces small and uniform in the centre, larger near the edges where the
bag's tension pushes on the sand).

(a) contacts whose midpoint lies in the band around the bag's mid-plane in y, as lines between
    the particle centres (projected on x-z), width and colour by the normal force: sand-sand in
    blues, bag-sand in reds, bag-bag (the fabric's particles touching each other) in green, width
    by force on the same scale, and the share of the section's normal force each kind carries;
(b) the bonds of the bag's central row (both ends within s/2 of the mid-plane in y), width and
    colour by tension (slack bonds thin grey);
(c) mean normal force against x in the section (bins of s = 5 mm), sand-sand and bag-sand.
Edge vs centre (stats): sand-sand contacts whose midpoint is within 2 s (10 mm) of the bag's
lateral boundary in plan (its current x and y extent) are "edge", the rest "centre"; the means are
over the whole bag and over the section.
"""
import numpy as np
import matplotlib
from matplotlib import cm, colors
from matplotlib.collections import LineCollection

from tbagspost import section, style
from tbagspost.section import masked_mean

EDGE = 2 * section.S
KINDS = {"sand-sand": (2, 2), "bag-sand": (1, 2), "bag-bag": (1, 1)}
LW = (0.3, 3.0)  # line width at zero and at the colour scale's top


def contact_kind(c):
    """Array of 'sand-sand', 'bag-sand', 'bag-bag' per contact."""
    lo, hi = np.minimum(c["type1"], c["type2"]), np.maximum(c["type1"], c["type2"])
    kind = np.full(len(lo), "bag-bag", dtype=object)
    kind[(lo == 1) & (hi == 2)] = "bag-sand"
    kind[(lo == 2) & (hi == 2)] = "sand-sand"
    return kind


def ends(g, a, b):
    """Positions (n, 2, 3) of the two atoms of each contact or bond (ids a, b)."""
    return np.stack([g.pos[g.index(a)], g.pos[g.index(b)]], axis=1)


def edge_mask(g, mid):
    """Midpoints (n, 3) within EDGE of the bag's lateral boundary in plan."""
    p = g.pos[g.bag]
    lo, hi = p[:, :2].min(axis=0), p[:, :2].max(axis=0)
    dist = np.minimum(mid[:, :2] - lo, hi - mid[:, :2]).min(axis=1)
    return dist < EDGE


def figure(run, step, half_band=None):
    """Figure of the contact network and bond tension at a dump step; returns (Figure, stats)."""
    g = run.grains(step)
    c = run.contacts(step)
    b = run.bonds(step)
    u = run.at_step(step)
    z_top = section.top_plate_z(run, step)
    half = half_band or section.default_half_band(g)
    yc = section.mid_y(g)

    seg = ends(g, c["id1"], c["id2"])
    mid = seg.mean(axis=1)
    kind = contact_kind(c)
    fn = c["fn"]
    in_sec = section.near_mid_y(g, mid, half)
    bseg = ends(g, b["id1"], b["id2"])
    b_sec = (np.abs(bseg[:, :, 1] - yc) <= section.S / 2).all(axis=1)

    fig, grid = style.grid_figure(3, 4, 7.0, 8.0, hspace=0.45, wspace=0.08, height_ratios=[1.2, 1.2, 1],
                                  width_ratios=[1, 0.025, 0.1, 0.025])
    a_net, a_bond, a_prof = fig.add_subplot(grid[0, 0]), fig.add_subplot(grid[1, 0]), fig.add_subplot(grid[2, 0])
    caxes = [fig.add_subplot(grid[0, 1]), fig.add_subplot(grid[0, 3]), fig.add_subplot(grid[1, 1])]
    xlo, xhi = g.pos[g.bag, 0].min(), g.pos[g.bag, 0].max()
    zmax = z_top if z_top is not None else float((g.pos[:, 2] + g.radius).max())
    shown = in_sec & (kind != "bag-bag")    # (the stats count the sand's contacts)
    fmax = max(float(fn[in_sec].max()) if in_sec.any() else 0.0, 1e-12)
    norm = colors.Normalize(0, fmax)
    bars = []
    for name, cmap in (("sand-sand", "Blues"), ("bag-sand", "Reds")):
        sel = in_sec & (kind == name)
        cmap = colors.LinearSegmentedColormap.from_list(name, matplotlib.colormaps[cmap](np.linspace(0.3, 1, 64)))
        section.segments_xz(a_net, seg[sel], np.clip(fn[sel], 0, None), norm, cmap, LW)
        bars.append((cm.ScalarMappable(norm=norm, cmap=cmap), "%s $f_n$ (N)" % name))
    wall = in_sec & (kind == "bag-bag")
    a_net.add_collection(LineCollection(seg[wall][:, :, [0, 2]] * 1000, colors="tab:green", capstyle="round",
                                        linewidths=section.line_widths(fn[wall], fmax, LW)))
    total = max(float(np.clip(fn[in_sec], 0, None).sum()), 1e-12)
    shares = ", ".join("%s %.0f %%" % (name, 100 * np.clip(fn[in_sec & (kind == name)], 0, None).sum() / total)
                       for name in KINDS)
    sec_bag = section.in_xz(g, half) & g.bag
    a_net.plot(g.pos[sec_bag, 0] * 1000, g.pos[sec_bag, 2] * 1000, "o", color="0.6", ms=1.2, zorder=0)
    a_net.set_title("contact forces, central x-z section $\\pm$%.1f mm ($u$ = %.2f mm), bag-bag in green\n"
                    "share of the section's normal force: %s" % (half * 1000, u, shares), fontsize=8)

    tension = b["tension"]
    bnorm = colors.Normalize(0, max(float(tension[b_sec].max()) if b_sec.any() else 0.0, 1e-12))
    slack = b_sec & (tension <= 0)
    a_bond.add_collection(LineCollection(bseg[slack][:, :, [0, 2]] * 1000, colors="0.7", linewidths=0.4))
    section.segments_xz(a_bond, bseg[b_sec & ~slack], tension[b_sec & ~slack], bnorm, cm.plasma, LW)
    bars.append((cm.ScalarMappable(norm=bnorm, cmap=cm.plasma), "bond tension (N)"))
    a_bond.set_title("bond tension along the bag, central x-z section (slack bonds grey)")
    for ax in (a_net, a_bond):
        section.frame(ax, "$x$ (mm)", xlo, xhi, zmax)
        section.plates(ax, xlo, xhi, z_top)
    for (sm, label), cax in zip(bars, caxes):
        cax.grid(False)
        bar = fig.colorbar(sm, cax=cax)
        bar.set_label(label, fontsize=7)
        bar.ax.tick_params(labelsize=7)

    edges = np.arange(xlo, xhi + section.S, section.S)
    centres = 0.5 * (edges[1:] + edges[:-1]) * 1000
    for name, color in (("sand-sand", "tab:blue"), ("bag-sand", "tab:red")):
        sel = in_sec & (kind == name)
        k = np.digitize(mid[sel, 0], edges) - 1
        ok = (k >= 0) & (k < len(centres))
        total = np.bincount(k[ok], weights=fn[sel][ok], minlength=len(centres))
        count = np.bincount(k[ok], minlength=len(centres))
        mean = np.where(count > 0, total / np.maximum(count, 1), np.nan)
        a_prof.plot(centres, mean, "o-", color=color, ms=3, label=name)
    a_prof.set_xlabel("$x$ (mm)")
    a_prof.set_ylabel("mean $f_n$ in the section (N)")
    a_prof.set_xlim(a_net.get_xlim())
    a_prof.legend(frameon=False)
    for ax, tag in zip((a_net, a_bond, a_prof), "abc"):
        style.panel_label(ax, "(%s)" % tag)

    ss = kind == "sand-sand"
    edge = edge_mask(g, mid)
    with_sand = kind != "bag-bag"
    stats = dict(run=run.name, step=step, u_mm=u, n_contacts=len(fn), n_section=int(shown.sum()),
                 fn_max_N=float(fn[with_sand].max()) if with_sand.any() else 0.0,
                 fn_max_bagbag_N=float(fn[~with_sand].max()) if (~with_sand).any() else 0.0,
                 fn_edge_N=masked_mean(fn, ss & edge), fn_centre_N=masked_mean(fn, ss & ~edge),
                 fn_edge_sec_N=masked_mean(fn, ss & edge & in_sec),
                 fn_centre_sec_N=masked_mean(fn, ss & ~edge & in_sec),
                 fn_bag_sand_N=masked_mean(fn, kind == "bag-sand"),
                 tension_max_N=float(tension.max()) if len(tension) else 0.0,
                 tension_mean_N=masked_mean(tension, tension > 0), slack=float((tension <= 0).mean()) if len(tension) else 0.0)
    return fig, stats


def describe(st):
    """One line of numbers for a network figure."""
    return ("%s u = %.2f mm: %d contacts (%d shown in the section), largest f_n on sand %.2f N (bag-bag "
            "%.2f N); sand-sand mean "
            "f_n near the edges %.3f N vs centre %.3f N (section: %.3f vs %.3f N), bag-sand mean %.3f N; "
            "bond tension max %.2f N, mean of taut bonds %.3f N, %.0f %% of bonds slack"
            % (st["run"], st["u_mm"], st["n_contacts"], st["n_section"], st["fn_max_N"], st["fn_max_bagbag_N"],
               st["fn_edge_N"],
               st["fn_centre_N"], st["fn_edge_sec_N"], st["fn_centre_sec_N"], st["fn_bag_sand_N"],
               st["tension_max_N"], st["tension_mean_N"], 100 * st["slack"]))
