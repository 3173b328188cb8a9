"""What carries the load: the forces that the contacts pass across a horizontal plane at the bag's
mid-height, split into sand-sand, bag-sand and bag-bag contacts.

The plane lies halfway between the two middle layers of the bag's grid (filled-state heights are
multiples of the 5 mm spacing), at their current mean height, so that no wall particle sits on
it. A contact crosses it when its two particles lie on either side. The vertical force through the
plane is the top plate's F_v (plus the weight above), all of it through contacts, since the yarn
bonds only pull. The horizontal force the contacts pass is compared with the top plate's S: the
rest crosses through the yarn bonds (axial tension, and the shear spring of bond_style bpm/yarn).
A sandbag whose sand is loaded shows most of F_v in sand contacts.
"""
from collections import OrderedDict

import numpy as np

SPACING = 0.005    # m, the bag grid


def mid_plane(g):
    """Height (m) of the plane halfway between the bag's two middle grid layers."""
    z0 = g.pos[:, 2] - g.disp[:, 2]
    bag = g.bag
    layer = np.rint((z0[bag] - z0[bag].min()) / SPACING).astype(int)
    below = (layer.max() - 1) // 2
    z = g.pos[bag, 2]
    return 0.5 * (z[layer == below].mean() + z[layer == below + 1].mean())


def through_plane(g, c, z=None):
    """Forces passed across the plane z (default mid_plane) by the contacts c: OrderedDict with
    z, the total vertical (compressive, N) and horizontal x force (N, on the part below) and, per
    class sand-sand / bag-sand / bag-bag, those two and the number of contacts."""
    z = mid_plane(g) if z is None else z
    i1, i2 = g.index(c["id1"]), g.index(c["id2"])
    p1, p2 = g.pos[i1], g.pos[i2]
    cross = (p1[:, 2] - z) * (p2[:, 2] - z) < 0
    d = p1 - p2
    n = d / np.linalg.norm(d, axis=1)[:, None]
    f1 = c["fn"][:, None] * n + np.column_stack([c["ftx"], c["fty"], c["ftz"]])    # force on 1
    f_low = np.where((p1[:, 2] > p2[:, 2])[:, None], -f1, f1)      # on the lower particle
    t1, t2 = c["type1"], c["type2"]
    classes = OrderedDict([("sand-sand", (t1 == 2) & (t2 == 2)), ("bag-sand", t1 != t2),
                           ("bag-bag", (t1 == 1) & (t2 == 1))])
    out = OrderedDict(z=float(z), Fz=float(-f_low[cross, 2].sum()), Fx=float(f_low[cross, 0].sum()))
    for name, m in classes.items():
        k = cross & m
        out[name] = (float(-f_low[k, 2].sum()), float(f_low[k, 0].sum()), int(k.sum()))
    return out


def describe(r, S=None):
    """One line: the share of the vertical force per contact class, and the contacts' share of S."""
    share = ", ".join("%s %.0f %%" % (k, 100 * r[k][0] / r["Fz"]) for k in ("sand-sand", "bag-sand", "bag-bag"))
    line = "load path at mid-height (z = %.1f mm): vertical %.0f N through contacts: %s" % (r["z"] * 1e3, r["Fz"], share)
    if S is not None:
        line += "; horizontal %.0f N through contacts of S = %.0f N (the rest through the yarn bonds)" % (r["Fx"], S)
    return line
