"""Geometry shared by the shape, network and forces figures: the central cross-sections of the bag,
particles drawn at their true size, the two plates.

Axes: x is the shear direction (the top plate moves +x), z is vertical; the bottom plate is the
plane z = -s/2 (s = 5 mm, the bag grid spacing), the top plate's z comes from the CSV (zplate_mm).
The x-z section keeps what lies within a band around the bag's mid-plane in y; the y-z section
keeps particles whose filled-state x (x - dx) lies within the band around the bag's mid-plane in
x, so it follows the same material slice while the bag is sheared.
"""
import numpy as np
from matplotlib.collections import EllipseCollection, LineCollection

S = 0.005          # m, bag grid spacing (in.bag)
Z_BOTTOM = -S / 2  # m, the bottom plate


def default_half_band(g):
    """Half width (m) of the section band: one mean sand diameter, at least s/2."""
    sand = g.radius[~g.bag]
    return max(S / 2, 2 * float(sand.mean()) if len(sand) else 0.0)


def mid_y(g):
    """The bag's mid-plane in y (m), from its bag particles now."""
    y = g.pos[g.bag, 1]
    return 0.5 * (y.min() + y.max())


def mid_x0(g):
    """The bag's mid-plane in x (m) in the filled state."""
    x0 = g.pos[g.bag, 0] - g.disp[g.bag, 0]
    return 0.5 * (x0.min() + x0.max())


def near_mid_y(g, points, half):
    """Mask of the points (n, 3; m) within half of the bag's mid-plane in y."""
    return np.abs(points[:, 1] - mid_y(g)) <= half


def in_xz(g, half):
    """Mask of the particles in the central x-z section (|y - mid| <= half)."""
    return near_mid_y(g, g.pos, half)


def in_yz(g, half):
    """Mask of the particles in the central y-z section (|x0 - mid| <= half, filled state x0)."""
    return np.abs(g.pos[:, 0] - g.disp[:, 0] - mid_x0(g)) <= half


def circles(ax, centres, radius, **kw):
    """Particles as circles of their true radius at centres (n, 2), both in the axes' data
    units (mm); returns the collection (pass array= and cmap= in kw to colour by a value)."""
    d = 2 * np.asarray(radius)
    col = EllipseCollection(d, d, np.zeros_like(d), units="xy", offsets=centres,
                            offset_transform=ax.transData, **kw)
    ax.add_collection(col)
    return col


def masked_mean(value, mask):
    """Mean of value where mask holds; nan where it holds nowhere (an empty band of contacts)."""
    return float(value[mask].mean()) if mask.any() else float("nan")


def line_widths(value, top, widths):
    """Line widths from widths[0] at value 0 to widths[1] at value top and above."""
    return widths[0] + (widths[1] - widths[0]) * np.clip(value / top, 0, 1)


def segments_xz(ax, seg, value, norm, cmap, widths, strongest_last=False):
    """Segments (n, 2, 3; m) drawn on x-z in mm, coloured by value and from widths[0] to widths[1]
    points wide as value goes from 0 to the colour scale's top; strongest_last: in order of value."""
    if strongest_last:
        order = np.argsort(value)
        seg, value = seg[order], value[order]
    col = LineCollection(seg[:, :, [0, 2]] * 1000, linewidths=line_widths(value, norm.vmax, widths),
                         cmap=cmap, norm=norm, capstyle="round")
    col.set_array(value)
    ax.add_collection(col)
    return col


def plates(ax, lo, hi, z_top=None, unit=1000.0):
    """The bottom plate and, when known, the top plate as thick grey lines from lo to hi (m)."""
    ax.plot([lo * unit, hi * unit], [Z_BOTTOM * unit] * 2, color="0.3", lw=2.5, solid_capstyle="butt")
    if z_top is not None:
        ax.plot([lo * unit, hi * unit], [z_top * unit] * 2, color="0.3", lw=2.5, solid_capstyle="butt")


def frame(ax, xlabel, lo, hi, zmax, unit=1000.0):
    """Equal-aspect axes in mm spanning lo..hi horizontally and the plates vertically."""
    ax.set_aspect("equal")
    pad = 0.05 * (hi - lo)
    ax.set_xlim((lo - pad) * unit, (hi + pad) * unit)
    ax.set_ylim((Z_BOTTOM - 0.06 * (zmax - Z_BOTTOM)) * unit, (zmax + 0.08 * (zmax - Z_BOTTOM)) * unit)
    ax.set_xlabel(xlabel)
    ax.set_ylabel("$z$ (mm)")
    ax.grid(False)


def top_plate_z(run, step):
    """Top plate z (m) at a dump step from the CSV's zplate_mm, or None for an older CSV."""
    if "zplate_mm" not in run.csv.dtype.names:
        return None
    return run.at_step(step, "zplate_mm") / 1000
