"""Deformed shape of the bag at one dump step (the paper's Part 2: the top surface detaches from
the top plate, the sides bulge, the deformation localizes).

Three panels, bag particles coloured by the magnitude of their displacement from the filled
state (mm), the filled-state positions as grey dots, the plates as thick lines:
(a) side view: all bag particles seen along y (nearest drawn last);
(b) central x-z cross-section (shear plane), sand grains in light grey;
(c) central y-z cross-section (across the shear direction), same.
Numbers (stats): largest displacement of bag and sand, the gap between the top plate and the top
surface of the bag (per 5 mm cell of the plan: plate z - max(z + r) of the bag particles in it),
the share of the top surface that is detached (gap > 0.1 mm), the largest outward bulge of the
side walls in the y-z section.
"""
import numpy as np
from matplotlib import cm, colors

from tbagspost import section, style

GAP_DETACHED_MM = 0.1


def top_gaps(g, z_top):
    """Gap (mm) between the top plate and the bag's top surface per s x s cell of the plan,
    for the interior cells (the outer ring of cells, the rounded edges, left out)."""
    bag = g.bag
    x, y, top = g.pos[bag, 0], g.pos[bag, 1], g.pos[bag, 2] + g.radius[bag]
    i = np.floor((x - x.min()) / section.S).astype(int)
    j = np.floor((y - y.min()) / section.S).astype(int)
    highest = np.full((i.max() + 1, j.max() + 1), -np.inf)
    np.maximum.at(highest, (i, j), top)
    inner = highest[1:-1, 1:-1]
    inner = inner[np.isfinite(inner)]
    return (z_top - inner) * 1000


def side_bulge(g, half):
    """Largest outward displacement (mm) of the side walls (|y0 - mid| in the outer 10 % of the
    half width, filled state) in the central y-z section, away from the plates."""
    sec = section.in_yz(g, half) & g.bag
    y0 = g.pos[sec, 1] - g.disp[sec, 1]
    z0 = g.pos[sec, 2] - g.disp[sec, 2]
    mid = 0.5 * (y0.min() + y0.max())
    halfw = 0.5 * (y0.max() - y0.min())
    wall = (np.abs(y0 - mid) > 0.9 * halfw) & (z0 > z0.min() + section.S / 2) & (z0 < z0.max() - section.S / 2)
    if not wall.any():
        return 0.0
    outward = np.sign(y0 - mid)[wall] * g.disp[sec, 1][wall]
    return float(outward.max() * 1000)


def figure(run, step, half_band=None):
    """Figure of the deformed bag at a dump step; returns (Figure, stats)."""
    g = run.grains(step)
    u = run.at_step(step)
    z_top = section.top_plate_z(run, step)
    half = half_band or section.default_half_band(g)
    dmag = np.linalg.norm(g.disp, axis=1) * 1000
    bag = g.bag
    norm = colors.Normalize(0, max(float(dmag[bag].max()), 1e-9))
    cmap = cm.viridis
    mm = 1000.0
    zmax = z_top if z_top is not None else float((g.pos[:, 2] + g.radius).max())

    fig, (a_side, a_xz, a_yz) = style.figure(3, 1, width=7.0, height=7.6, gridspec_kw=dict(hspace=0.5))

    # (a) side view along y: all bag particles, those at larger y (nearer a viewer at +y) on top
    order = np.argsort(g.pos[bag, 1])
    p, r, d = g.pos[bag][order], g.radius[bag][order], dmag[bag][order]
    section.circles(a_side, p[:, [0, 2]] * mm, r * mm, array=d, cmap=cmap, norm=norm, edgecolors="none")
    xlo, xhi = g.pos[:, 0].min(), g.pos[:, 0].max()
    section.frame(a_side, "$x$ (mm)", xlo, xhi, zmax)
    section.plates(a_side, xlo, xhi, z_top)
    a_side.set_title("side view, all bag particles ($u$ = %.2f mm)" % u)

    # (b), (c) central sections: sand grey, bag coloured, filled-state bag positions as dots
    for ax, sel, (h, name), title in (
            (a_xz, section.in_xz(g, half), (0, "$x$"), "central x-z section (shear plane)"),
            (a_yz, section.in_yz(g, half), (1, "$y$"), "central y-z section")):
        sand, sbag = sel & ~bag, sel & bag
        section.circles(ax, g.pos[sand][:, [h, 2]] * mm, g.radius[sand] * mm, facecolors="0.85",
                        edgecolors="0.6", linewidths=0.3)
        section.circles(ax, g.pos[sbag][:, [h, 2]] * mm, g.radius[sbag] * mm, array=dmag[sbag], cmap=cmap,
                        norm=norm, edgecolors="k", linewidths=0.2)
        p0 = (g.pos[sbag] - g.disp[sbag])[:, [h, 2]] * mm
        ax.plot(p0[:, 0], p0[:, 1], "+", color="k", ms=3, mew=0.5, label="bag, filled state")
        lo, hi = g.pos[sel, h].min(), g.pos[sel, h].max()
        section.frame(ax, name + " (mm)", lo, hi, zmax)
        section.plates(ax, lo, hi, z_top)
        ax.set_title(title + ", band $\\pm$%.1f mm" % (half * mm))
    for ax, tag in zip((a_side, a_xz, a_yz), "abc"):
        style.panel_label(ax, "(%s)" % tag)
    a_yz.legend(loc="upper center", bbox_to_anchor=(0.5, -0.3), frameon=False, fontsize=7)
    bar = fig.colorbar(cm.ScalarMappable(norm=norm, cmap=cmap), ax=[a_side, a_xz, a_yz], shrink=0.5,
                       pad=0.03, aspect=30)
    bar.set_label("bag displacement from the filled state (mm)")

    stats = dict(run=run.name, step=step, u_mm=u, d_bag_max_mm=float(dmag[bag].max()),
                 d_sand_max_mm=float(dmag[~bag].max()) if (~bag).any() else 0.0,
                 bulge_mm=side_bulge(g, half))
    if z_top is not None:
        gaps = top_gaps(g, z_top)
        stats.update(gap_max_mm=float(gaps.max()), gap_median_mm=float(np.median(gaps)),
                     detached=float((gaps > GAP_DETACHED_MM).mean()))
        a_side.set_title("side view, all bag particles ($u$ = %.2f mm; top surface: gap to the plate "
                         "up to %.2f mm, %.0f %% detached)" % (u, stats["gap_max_mm"], 100 * stats["detached"]))
    return fig, stats


def describe(st):
    """One line of numbers for a deformed-shape figure."""
    line = ("%s u = %.2f mm: largest displacement bag %.2f mm, sand %.2f mm; side walls bulge "
            "outward up to %.2f mm" % (st["run"], st["u_mm"], st["d_bag_max_mm"], st["d_sand_max_mm"],
                                        st["bulge_mm"]))
    if "gap_max_mm" in st:
        line += ("; top surface: gap to the top plate up to %.2f mm (median %.2f mm), %.0f %% of it "
                 "detached (> %.1f mm)" % (st["gap_max_mm"], st["gap_median_mm"], 100 * st["detached"],
                                           GAP_DETACHED_MM))
    return line
