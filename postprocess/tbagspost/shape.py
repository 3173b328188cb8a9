"""Deformed shape of the bag at one dump step (the paper's Part 2: the top surface detaches from
the top plate, the sides bulge, the deformation localizes).

Three panels, bag particles coloured by the magnitude of their displacement from the filled
state (mm), the filled-state positions as grey dots, the plates as thick lines:
(a) side view: all bag particles seen along y (nearest drawn last);
(b) central x-z cross-section (shear plane), sand grains in light grey;
(c) central y-z cross-section (across the shear direction), same;
(d) the gap between the top plate and the bag's top surface along x in the x-z section;
(e) the bulge of the four walls against height (outward distance from the chord joining the
    wall's lowest and highest particle, free of the shear tilt and of a sideways drift).
Numbers (stats): largest displacement of bag and sand, the gap between the top plate and the top
surface of the bag (per 5 mm cell of the plan: plate z - max(z + r) of the bag particles in it),
the share of the top surface that is detached (gap > 0.1 mm), the largest bulge of each wall.
"""
import numpy as np
from matplotlib import cm, colors

from tbagspost import section, style

GAP_DETACHED_MM = 0.1


def top_layer(g):
    """Mask of the bag's top face: bag particles on the highest level of the filled state."""
    z0 = g.pos[:, 2] - g.disp[:, 2]
    return g.bag & (z0 > z0[g.bag].max() - section.S / 2)


def top_gaps(g, z_top):
    """Gap (mm) between the top plate and each particle of the bag's top face (z + r), for the
    interior of the face (its outer ring, the rounded edges, left out); particles are picked by
    their filled-state position, so the face is followed as it shears."""
    top = top_layer(g)
    p0 = g.pos[top] - g.disp[top]
    inner = np.ones(len(p0), dtype=bool)
    for h in (0, 1):
        inner &= (p0[:, h] > p0[:, h].min() + section.S / 2) & (p0[:, h] < p0[:, h].max() - section.S / 2)
    return (z_top - g.pos[top, 2] - g.radius[top])[inner] * 1000


def gap_profile(g, z_top, sel):
    """Gap (mm) between the top plate and the bag's top face along x among the particles sel:
    per grid column (filled-state x), plate z - max(z + r); returns (mean x now in mm, gap in mm)."""
    top = top_layer(g) & sel
    column = np.round((g.pos[top, 0] - g.disp[top, 0]) / section.S).astype(int)
    x, height = g.pos[top, 0], g.pos[top, 2] + g.radius[top]
    keys = np.unique(column)
    xs = np.array([x[column == k].mean() for k in keys])
    highest = np.array([height[column == k].max() for k in keys])
    return xs * 1000, (z_top - highest) * 1000


WALLS = (("trailing wall ($-x$)", 0, -1), ("leading wall ($+x$)", 0, 1),
         ("side wall $-y$", 1, -1), ("side wall $+y$", 1, 1))


def wall_profiles(g, half):
    """Bulging of the four walls in the central sections (x walls in the x-z section, y walls
    in the y-z section). A wall is the bag particles in the outer 10 % of the section's half
    length (filled state), taken level by level (5 mm rows of filled-state height, the band's
    rows averaged); its bulge is the outward distance of each level from the straight line
    (chord) joining the wall's bottom and top levels now, so neither the shear tilt nor a
    sideways shift of the whole wall counts. Returns [(name, z in mm, outward bulge in mm)]."""
    out = []
    for name, h, side in WALLS:
        sel = (section.in_xz(g, half) if h == 0 else section.in_yz(g, half)) & g.bag
        p, p0 = g.pos[sel], g.pos[sel] - g.disp[sel]
        mid, halfw = 0.5 * (p0[:, h].min() + p0[:, h].max()), 0.5 * (p0[:, h].max() - p0[:, h].min())
        wall = side * (p0[:, h] - mid) > 0.9 * halfw
        level = np.round((p0[wall, 2] - p0[wall, 2].min()) / section.S).astype(int)
        rows = np.array([p[wall][level == k].mean(axis=0) for k in np.unique(level)])
        if len(rows) < 3:
            continue
        lo, hi = rows[0], rows[-1]
        chord = lo[h] + (hi[h] - lo[h]) * (rows[1:-1, 2] - lo[2]) / (hi[2] - lo[2])
        out.append((name, rows[1:-1, 2] * 1000, side * (rows[1:-1, h] - chord) * 1000))
    return out


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

    fig, grid = style.grid_figure(4, 3, 7.0, 9.6, hspace=0.55, wspace=0.3, height_ratios=[1, 1, 1, 0.9],
                                  width_ratios=[1, 1, 0.035])
    a_side, a_xz, a_yz = (fig.add_subplot(grid[k, :2]) for k in range(3))
    cax = fig.add_subplot(grid[:3, 2])
    cax.grid(False)
    a_gap, a_bulge = fig.add_subplot(grid[3, 0]), fig.add_subplot(grid[3, 1])

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
        ax.set_title(title + ", band $\\pm$%.1f mm (+: filled state)" % (half * mm))
    # (d) top-surface gap along x in the x-z section; (e) outward bulge of the side walls
    if z_top is not None:
        xg, gap = gap_profile(g, z_top, section.in_xz(g, half) & bag)
        a_gap.plot(xg, gap, "o-", ms=3, color="tab:blue")
    a_gap.axhline(GAP_DETACHED_MM, color="0.5", lw=0.6, ls="--")
    a_gap.set_xlabel("$x$ (mm)")
    a_gap.set_ylabel("gap top plate - bag (mm)")
    a_gap.set_title("top gap, central x-z section")
    walls = wall_profiles(g, half)
    for (name, zw, off), marker in zip(walls, "<>v^"):
        a_bulge.plot(off, zw, marker + "-", ms=3, lw=0.8, label=name)
    a_bulge.axvline(0, color="0.5", lw=0.6)
    a_bulge.set_xlabel("outward bulge from the wall's chord (mm)")
    a_bulge.set_ylabel("$z$ (mm)")
    a_bulge.set_title("walls, central sections")
    a_bulge.legend(frameon=False, fontsize=6)
    a_bulge.legend(frameon=False, fontsize=7)
    for ax, tag in zip((a_side, a_xz, a_yz, a_gap, a_bulge), "abcde"):
        style.panel_label(ax, "(%s)" % tag)
    bar = fig.colorbar(cm.ScalarMappable(norm=norm, cmap=cmap), cax=cax)
    bar.set_label("bag displacement from the filled state (mm)")

    stats = dict(run=run.name, step=step, u_mm=u, d_bag_max_mm=float(dmag[bag].max()),
                 d_sand_max_mm=float(dmag[~bag].max()) if (~bag).any() else 0.0,
                 bulge_mm={name.replace("$", ""): float(off.max()) for name, _, off in walls})
    if z_top is not None:
        gaps = top_gaps(g, z_top)
        stats.update(gap_max_mm=float(gaps.max()), gap_median_mm=float(np.median(gaps)),
                     detached=float((gaps > GAP_DETACHED_MM).mean()))
        a_gap.set_title("top gap, central section (whole top: max %.2f mm,\n%.0f %% of it > %.1f mm)"
                        % (stats["gap_max_mm"], 100 * stats["detached"], GAP_DETACHED_MM), fontsize=8)
    return fig, stats


def describe(st):
    """One line of numbers for a deformed-shape figure."""
    line = ("%s u = %.2f mm: largest displacement bag %.2f mm, sand %.2f mm; walls bulge outward from "
            "their chord by up to %s" % (st["run"], st["u_mm"], st["d_bag_max_mm"], st["d_sand_max_mm"],
                                         ", ".join("%.2f mm (%s)" % (v, k) for k, v in st["bulge_mm"].items())))
    if "gap_max_mm" in st:
        line += ("; top surface: gap to the top plate up to %.2f mm (median %.2f mm), %.0f %% of it "
                 "detached (> %.1f mm)" % (st["gap_max_mm"], st["gap_median_mm"], 100 * st["detached"],
                                           GAP_DETACHED_MM))
    return line
