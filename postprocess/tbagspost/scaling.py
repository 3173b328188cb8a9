"""The paper bag's work per MPI rank under LAMMPS's domain decomposition, and the cluster scaling
model built on it (./tbags shear paper --estimate; project_time.py prints it).

Counts. LAMMPS splits the box into a Px x Py x Pz grid of equal bricks, the grid of least
sub-domain surface (procmap.cpp's rule, redone here: grid()); a rank owns the atoms in its brick
and holds as ghosts the other atoms within the communication cutoff of it (0.010 m: comm_modify
in the decks). From a checkpoint's data file (positions, diameters, bonds) and the plates' heights,
counts() gives per rank: owned atoms, ghosts, neighbour pairs (closer than the sum of radii plus
the skin; half list with newton on: a pair across two bricks on the rank of its lower atom), bonds
(on the rank owning their first atom) and plate atoms (within 1.5 skins of a plate: fix
wall/gran/servo's candidates). Short runs of the same checkpoint at P ranks give LAMMPS's own
grid and its Nlocal, Nghost and Neighs (mean and max over ranks); check() compares them.

Model. One step of rank r costs
    t_r = c_pair neigh_r + c_bond bonds_r + c_atom owned_r + c_ghost ghosts_r
          + m_r alpha + B ghosts_r beta + n_sum log2(P) alpha
and the step takes the largest t_r (the other ranks wait in Comm). Measured on this machine:
c_pair, c_bond (Pair and Bond time per neighbour pair and per bond of the 1-rank run), c_atom
(the rest of that run, Comm aside, per atom: plates, integrator, gravity, neighbour lists,
averages), c_ghost (the 2-rank run's Comm time on its less-waiting rank, per ghost: packing,
copying and unpacking in shared memory). Assumed for a cluster's network (NETWORK): alpha, the
latency of one message; beta, the time per byte; m_r = 4 messages per split dimension (a swap
each way, forward and reverse communication); B = 120 bytes per ghost and step (position,
velocity, angular velocity out; force and torque back); n_sum = 4 global sums per step (the two
plates' forces, the neighbour-list decision, the pair's candidate-list decision).
Efficiency at P ranks = t(1) / (P t(P)).
"""
import math

import numpy as np
from scipy.spatial import cKDTree

CUT_COMM = 0.010        # m, comm_modify cutoff of the decks
SKIN = 0.001            # m, the neighbour skin (neighbor 0.001 bin: inputs/sand.lmp)
PLATE_REACH = 1.5 * SKIN
NETWORK = dict(alpha=2e-6, beta=1e-10, bytes_per_ghost=120, sums_per_step=4)
NETWORK_TEXT = ("network assumed: %.1f us per message (an InfiniBand-class interconnect), "
                "%.0f GB/s, %d bytes per ghost-step, %d global sums per step"
                % (NETWORK["alpha"] * 1e6, 1e-9 / NETWORK["beta"], NETWORK["bytes_per_ghost"],
                   NETWORK["sums_per_step"]))


def grid(ranks, lengths):
    """LAMMPS's processor grid for `ranks` on a box of edge lengths (lx, ly, lz): of all
    factorisations px py pz = ranks (px, then py ascending) the first of least sub-domain surface."""
    lx, ly, lz = lengths
    best, best_surf = None, 2.0 * (lx * ly + lx * lz + ly * lz)
    for px in range(1, ranks + 1):
        if ranks % px:
            continue
        for py in range(1, ranks // px + 1):
            if (ranks // px) % py:
                continue
            pz = ranks // px // py
            surf = lx * ly / px / py + lx * lz / px / pz + ly * lz / py / pz
            if surf < best_surf:
                best, best_surf = (px, py, pz), surf
    return best


def owner_cells(x, box, procgrid):
    """Each atom's brick index (ix, iy, iz) in the uniform grid."""
    lo, length = box[:, 0], box[:, 1] - box[:, 0]
    cell = np.floor((x - lo) / length * np.array(procgrid)).astype(int)
    return np.clip(cell, 0, np.array(procgrid) - 1)


def pair_owners(data):
    """For each neighbour pair (closer than r_i + r_j + skin; bonded pairs too: the list keeps
    them, the pair skips them), the atom whose rank lists it: with newton on a pair across two
    bricks is listed by the rank of its lower atom (z, then y, then x decide, as LAMMPS's
    half/size/bin/newton list keeps a ghost only above its owned atom)."""
    x, r = data.x, 0.5 * data.diameter
    pairs = cKDTree(x).query_pairs(2 * r.max() + SKIN, output_type="ndarray")
    i, j = pairs[:, 0], pairs[:, 1]
    near = np.linalg.norm(x[i] - x[j], axis=1) < r[i] + r[j] + SKIN
    i, j = i[near], j[near]
    xi, xj = x[i], x[j]
    j_above = (xj[:, 2] > xi[:, 2]) | ((xj[:, 2] == xi[:, 2]) & ((xj[:, 1] > xi[:, 1]) |
                                                               ((xj[:, 1] == xi[:, 1]) & (xj[:, 0] > xi[:, 0]))))
    return np.where(j_above, i, j)


def counts(data, ranks, plates, owners=None):
    """Per-rank counts (arrays of length `ranks`) of the data file's atoms decomposed on `ranks`
    ranks: owned, ghosts, neigh, bonds, plate (plates: the bottom and top plates' heights, m;
    owners: pair_owners(data), when already found for another rank count)."""
    box, x, r = data.box, data.x, 0.5 * data.diameter
    procgrid = grid(ranks, box[:, 1] - box[:, 0])
    cell = owner_cells(x, box, procgrid)
    rank = np.ravel_multi_index(cell.T, procgrid)
    out = dict(grid=procgrid)
    out["owned"] = np.bincount(rank, minlength=ranks)
    # ghosts: atoms of other bricks inside a brick grown by the cutoff
    edges = [box[k, 0] + (box[k, 1] - box[k, 0]) * np.arange(procgrid[k] + 1) / procgrid[k] for k in range(3)]
    ghosts = np.zeros(ranks, dtype=int)
    for flat in range(ranks):
        c = np.unravel_index(flat, procgrid)
        inside = np.ones(len(x), dtype=bool)
        for k in range(3):
            inside &= (x[:, k] >= edges[k][c[k]] - CUT_COMM) & (x[:, k] < edges[k][c[k] + 1] + CUT_COMM)
        ghosts[flat] = np.count_nonzero(inside) - out["owned"][flat]
    out["ghosts"] = ghosts
    out["neigh"] = np.bincount(rank[pair_owners(data) if owners is None else owners], minlength=ranks)
    out["bonds"] = np.bincount(rank[data.index(data.bonds[:, 0])], minlength=ranks)
    zlo, zhi = plates
    plate = (x[:, 2] - r - zlo < PLATE_REACH) | (zhi - x[:, 2] - r < PLATE_REACH)
    out["plate"] = np.bincount(rank[plate], minlength=ranks)
    return out


def costs(one, two, totals):
    """The per-item costs (s) from the 1-rank and 2-rank runs' sections (dicts of section ->
    seconds per step; two['Comm_min']: the 2-rank run's least Comm time per step) and the
    1-rank counts `totals` (neigh, bonds, owned) and 2-rank ghosts per rank (totals['ghosts2'])."""
    rest = one["total"] - one["Pair"] - one["Bond"] - one.get("Comm", 0.0)
    return dict(c_pair=one["Pair"] / totals["neigh"], c_bond=one["Bond"] / totals["bonds"],
                c_atom=rest / totals["owned"],
                c_ghost=two["Comm_min"] / totals["ghosts2"] if totals["ghosts2"] else 0.0)


def step_time(c, n, ranks, network=NETWORK):
    """The model's time of one step (s) at `ranks` ranks from per-rank counts n."""
    split = sum(1 for p in n["grid"] if p > 1)
    t = (c["c_pair"] * n["neigh"] + c["c_bond"] * n["bonds"] + c["c_atom"] * n["owned"]
         + (c["c_ghost"] + network["bytes_per_ghost"] * network["beta"]) * n["ghosts"]
         + 4 * split * network["alpha"])
    if ranks > 1:
        t = t + network["sums_per_step"] * math.log2(ranks) * network["alpha"]
    return float(np.max(t))


def check(n, lammps_stats, tolerance=(0.02, 0.05)):
    """The counts against LAMMPS's own (grid, and mean/max of Nlocal, Nghost, Neighs): a list of
    discrepancies beyond `tolerance` (relative; means, maxima), empty when they agree. Maxima get
    more: LAMMPS gives a pair across two bricks to one side by the order of its neighbour bins, not
    of the atoms' coordinates, which moves a few % of pairs between the busiest rank and the next."""
    bad = []
    if tuple(lammps_stats["grid"]) != tuple(n["grid"]):
        bad.append("grid %s, LAMMPS %s" % (n["grid"], lammps_stats["grid"]))
    for ours, theirs in (("owned", "Nlocal"), ("ghosts", "Nghost"), ("neigh", "Neighs")):
        for stat, f, tol in (("ave", np.mean, tolerance[0]), ("max", np.max, tolerance[1])):
            a, b = float(f(n[ours])), lammps_stats[theirs][stat]
            if abs(a - b) > tol * max(b, 1.0):
                bad.append("%s %s %.0f, LAMMPS %s %.0f" % (ours, stat, a, theirs, b))
    return bad
