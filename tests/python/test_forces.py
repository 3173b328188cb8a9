"""postprocess/tbagspost/forces (the paper's Fig. 5 views) on a made-up bulging bag: the resultant
takes the tangential force too, and the side band follows the sand's front face where the wall
bulges (the band measured from the sand's lowest y anywhere keeps only the belly of the bulge)."""
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "postprocess"))
from tbagspost import forces  # noqa: E402
from tbagspost.dumps import Grains  # noqa: E402

L, H, BULGE, R = 0.2, 0.05, 0.02, 0.0025    # m: the bag's length and height, the wall's bulge at
                                             # mid-length and mid-height, the bag particles' radius


def face(x, z):
    """The front wall now: bulging outwards (to -y) most at mid-length and mid-height."""
    return -BULGE * np.sin(np.pi * x / L) * np.sin(np.pi * z / H)


def bulging_bag():
    """The bag's front wall (a 5 mm grid in x-z, filled at y = 0, now on the bulging face), its back
    wall at y = 0.1 m and a sand grain, all as Grains."""
    xs, zs = np.arange(0.0, L + 1e-9, 0.005), np.arange(0.0, H + 1e-9, 0.005)
    front = np.array([(x, face(x, z), z) for x in xs for z in zs])
    back = np.array([(x, 0.1, z) for x in xs for z in zs])
    pos = np.vstack([front, back, [(L / 2, 0.05, H / 2)]])
    n = len(pos)
    disp = np.zeros((n, 3))
    disp[:len(front), 1] = front[:, 1]    # the filled state: the front wall flat at y = 0
    return Grains(step=0, ids=np.arange(1, n + 1), types=np.array([1] * (2 * len(front)) + [2]),
                  radius=np.full(n, R), pos=pos, vel=np.zeros((n, 3)), disp=disp, lo=np.zeros(3), hi=np.ones(3))


def test_the_resultant_takes_both_parts():
    c = dict(fn=np.array([3.0, 0.0]), ftx=np.array([4.0, 0.0]), fty=np.array([0.0, 2.0]), ftz=np.zeros(2))
    assert forces.resultant(c) == pytest.approx([5.0, 2.0])


def test_the_front_wall_is_the_grids_lowest_row():
    g = bulging_bag()
    wall = forces.front_wall(g)
    assert wall.sum() == 41 * 11 and (g.pos[wall, 1] <= 0).all() and not wall[-1]


def test_the_side_band_follows_the_bulging_wall():
    g = bulging_bag()
    half = 0.0025      # the band: within 5 mm of the wall's surface
    x = np.array([0.1, 0.1, 0.01, 0.01, 0.1, 0.1, 0.1])
    z = np.array([0.025, 0.025, 0.025, 0.025, 0.0075, 0.0075, 0.025])
    depth = R + np.array([0.002, 0.008, 0.002, 0.008, 0.002, 0.008, 0.0049])    # from the wall's centres
    mid = np.column_stack([x, face(x, z) + depth, z])
    centre, side = forces.bands(g, mid, half)
    assert side.tolist() == [True, False, True, False, True, False, True]
    assert not centre.any()    # the bag's mid-plane in y is at 40 mm (the wall bulges 20 mm)
    # measured from the lowest y anywhere, as a plane, only the belly of the bulge would count
    flat = mid[:, 1] - g.pos[forces.front_wall(g), 1].min() - R <= 2 * half
    assert flat.tolist() != side.tolist()
