"""The resultant contact forces on the sand in the paper's three views (Part 2, Fig. 5: the 3D
view, the section along the centre plane, the view from the side).

A contact's resultant is |f| = sqrt(f_n^2 + |f_t|^2) from the contact dump; the contacts "in the
sand" are those with a sand grain (sand-sand and bag-sand). Each contact is a line between its
two particle centres, coloured by its resultant on one scale for the three panels (0 to the 99.5th
percentile, so that a few outliers do not wash the colours out):
(a) 3D: the strongest contacts (at most N_3D, those above twice the mean), the bag's particles as
    faint dots;
(b) centre section: contacts whose midpoint lies within the band around the bag's mid-plane in y
    (section.default_half_band), projected on x-z;
(c) side: contacts whose midpoint lies within twice that half band of the bag's front wall (the
    grid's lowest row in y; distance to the nearest wall particle's surface, so that the band
    follows the bulging wall), projected on x-z: the sand one sees through the side wall.
Stats: the mean resultant in the centre section and in the side band and their ratio (the paper:
forces "relatively small and uniform" at the centre, "larger" at the edge).
"""
import numpy as np
from matplotlib import cm, colors
from mpl_toolkits.mplot3d.art3d import Line3DCollection
from scipy.spatial import cKDTree

from tbagspost import network, section, style
from tbagspost.section import masked_mean

N_3D = 20000     # most lines drawn in the 3D view (a figure that opens in a second)
LW = (0.2, 2.0)  # line width at zero and at the colour scale's top


def resultant(c):
    """|f| (N) of each contact: normal and tangential together."""
    return np.sqrt(c["fn"] ** 2 + c["ftx"] ** 2 + c["fty"] ** 2 + c["ftz"] ** 2)


def front_wall(g):
    """Mask of the bag's front wall: the particles of the grid's lowest row in y (filled state)."""
    y0 = g.pos[:, 1] - g.disp[:, 1]
    return g.bag & (y0 <= y0[g.bag].min() + section.S / 2)


def bands(g, mid, half):
    """Masks of the contacts (midpoints mid, m) in the centre section and in the side band: within
    2 half of the front wall's surface (the nearest wall particle's centre less its radius), which
    follows the wall where it bulges."""
    centre = section.near_mid_y(g, mid, half)
    wall = np.flatnonzero(front_wall(g))
    dist, k = cKDTree(g.pos[wall]).query(mid)
    side = dist - g.radius[wall][k] <= 2 * half
    return centre, side


def figure(run, step, half_band=None):
    """Figure of the three views at a dump step; returns (Figure, stats)."""
    g, c = run.grains(step), run.contacts(step)
    u = run.at_step(step)
    z_top = section.top_plate_z(run, step)
    half = half_band or section.default_half_band(g)
    on_sand = network.contact_kind(c) != "bag-bag"
    seg = network.ends(g, c["id1"], c["id2"])[on_sand]
    f = resultant(c)[on_sand]
    mid = seg.mean(axis=1)
    centre, side = bands(g, mid, half)
    top = max(float(np.percentile(f, 99.5)) if len(f) else 0.0, 1e-12)
    norm, cmap = colors.Normalize(0, top), cm.viridis

    fig, grid = style.grid_figure(3, 2, 7.0, 6.8, height_ratios=[1.25, 1, 1], width_ratios=[1, 0.025],
                                  hspace=0.3, wspace=0.05)
    a3 = fig.add_subplot(grid[0, 0], projection="3d")
    strong = np.flatnonzero(f > 2 * f.mean()) if len(f) else np.array([], dtype=int)
    strong = strong[np.argsort(f[strong])][-N_3D:]
    lines = Line3DCollection(seg[strong] * 1000, linewidths=section.line_widths(f[strong], top, LW) * 0.6, cmap=cmap, norm=norm)
    lines.set_array(f[strong])
    a3.add_collection3d(lines)
    bag = g.pos[g.bag][::3] * 1000
    a3.scatter(bag[:, 0], bag[:, 1], bag[:, 2], s=0.2, color="0.75", alpha=0.3, depthshade=False)
    lo, hi = g.pos[g.bag].min(axis=0) * 1000, g.pos[g.bag].max(axis=0) * 1000
    for axis, a, b in zip("xyz", lo, hi):
        getattr(a3, "set_%slim" % axis)(a, b)
        getattr(a3, "set_%slabel" % axis)("$%s$ (mm)" % axis, labelpad=-4)
    a3.set_box_aspect(hi - lo, zoom=1.3)
    a3.set_zticks(np.round(np.linspace(lo[2], hi[2], 3), -1))
    a3.view_init(elev=18, azim=-50)
    a3.tick_params(labelsize=6, pad=-2)
    a3.set_title("3D: the %d strongest contacts on sand (|f| > 2 x mean %.2f N), $u$ = %.2f mm"
                 % (len(strong), f.mean() if len(f) else 0.0, u), fontsize=8)

    xlo, xhi = lo[0] / 1000, hi[0] / 1000
    zmax = z_top if z_top is not None else float((g.pos[:, 2] + g.radius).max())
    views = ((centre, "centre section: contacts within $\\pm$%.1f mm of the bag's mid-plane in y" % (half * 1000)),
             (side, "side: contacts within %.1f mm of the bag's front wall (lowest y)" % (2 * half * 1000)))
    for row, (mask, title) in enumerate(views, start=1):
        ax = fig.add_subplot(grid[row, 0])
        section.segments_xz(ax, seg[mask], f[mask], norm, cmap, LW, strongest_last=True)
        section.frame(ax, "$x$ (mm)", xlo, xhi, zmax)
        section.plates(ax, xlo, xhi, z_top)
        ax.set_title("%s; mean |f| %.3f N" % (title, masked_mean(f, mask)), fontsize=8)
        style.panel_label(ax, "(%s)" % "abc"[row])
    a3.text2D(0.0, 0.95, "(a)", transform=a3.transAxes, fontweight="bold")
    cax = fig.add_subplot(grid[1:, 1])
    cax.grid(False)
    bar = fig.colorbar(cm.ScalarMappable(norm=norm, cmap=cmap), cax=cax)
    bar.set_label("resultant contact force |f| on sand (N)", fontsize=7)
    bar.ax.tick_params(labelsize=7)

    stats = dict(run=run.name, step=step, u_mm=u, n_sand_contacts=len(f), n_3d=len(strong),
                 mean_N=masked_mean(f, np.ones(len(f), bool)), p995_N=top,
                 centre_N=masked_mean(f, centre), side_N=masked_mean(f, side),
                 n_centre=int(centre.sum()), n_side=int(side.sum()))
    stats["side_over_centre"] = stats["side_N"] / stats["centre_N"] if stats["centre_N"] > 0 else float("nan")
    return fig, stats


def describe(st):
    """One line of numbers for a forces figure."""
    return ("%s u = %.2f mm: %d contacts on sand, mean |f| %.3f N (99.5th percentile %.2f N); centre section "
            "%.3f N (%d contacts), side band %.3f N (%d), side/centre %.2f"
            % (st["run"], st["u_mm"], st["n_sand_contacts"], st["mean_N"], st["p995_N"], st["centre_N"],
               st["n_centre"], st["side_N"], st["n_side"], st["side_over_centre"]))
