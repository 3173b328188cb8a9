"""Projected wall time of the paper-size simple shear protocol from a measured short stretch of
its own bag, and the scaling model over ranks (scaling.py).

usage: PYTHONPATH=postprocess /usr/bin/python3 -m tbagspost.project_time ESTIMATE_DIR --shared F [--ranks N]

ESTIMATE_DIR is the `./tbags shear paper --estimate` layout: the bag's and fill's logs in its
parent folder (the paper run's own), state/ (compression and a short shear to a checkpoint:
state.data, shear.csv, log.shear), np<P>/log.shear (a short stretch resumed from the checkpoint
at P ranks) and decomp/np<P>/log.shear (a few steps at P ranks: LAMMPS's decomposition). DEM
cost is linear in the number of particles at fixed density, so the measured cost per
particle-step of the shear stage at P ranks is applied to the paper's bag (measured on the
paper's bag itself, the factor is 1). Assumptions, printed with the table: the fill costs no more
per particle-step than shearing (its grains grow from half size); compression takes the measured
number of steps (times the ratio of sand heights on a smaller bag), of which the loads share those
before the force first reaches the shared fraction of the smallest load (./tbags shear runs that
part once, to the fraction F of the smallest load that the launcher passes as --shared: the part's own steps, compress/log.shear
beside the estimate, when the checkpoint continued from it; else from the checkpoint's thermo
output, every 2,000 steps, the last row below it); shearing takes u_final / (v dt) steps per load
(dt of the measured run).
"""
import argparse
import math
import re
import sys
from pathlib import Path

from . import scaling
from .datafile import DataFile
from .run import bag_size, log_timestep, loops, read_csv

# the paper's protocol (doc/tbags_model.rst section 4)
PAPER = dict(nx=81, ny=81, nz=17, loads=(5500, 3730, 1960), v=0.004, ufinal=0.015)
MODEL_RANKS = (1, 2, 4, 8, 16, 32, 64, 128, 256)
ZBOT = -0.0025    # m, the bottom plate (between_plates.lmp: -s/2)


def runs(log):
    """The completed runs of a LAMMPS log; stops clearly when it is missing or has none."""
    if not log.is_file():
        raise SystemExit("project_time: no %s (run ./tbags shear paper --estimate)" % log)
    found = loops(log.read_text(errors="replace"))
    if not found:
        raise SystemExit("project_time: %s has no completed run (truncated?)" % log)
    return found


def timestep(shear_log):
    """The time step of the measured shear run (its TIMESTEP line)."""
    dt = log_timestep(shear_log)
    if dt is None:
        raise SystemExit("project_time: %s has no TIMESTEP line" % shear_log)
    return dt


D_MIN, D_STEP, E0 = 3.60465e-3, 0.310078e-3, 0.68


def shared_steps(log, force):
    """Steps of the first run (the compression) in log before its thermo force column (v_Fmeas)
    first reaches `force`: its last thermo row below it (0 without thermo rows)."""
    below, cols = 0, None
    for line in log.read_text(errors="replace").splitlines():
        words = line.split()
        if cols is None:
            if words[:1] == ["Step"] and "v_Fmeas" in words:
                cols = (words.index("Step"), words.index("v_Fmeas"))
            continue
        if line.startswith("Loop time"):
            break
        try:
            step, f = int(words[cols[0]]), float(words[cols[1]])
        except (ValueError, IndexError):
            continue
        if f >= force:
            break
        below = step
    return below


def first_step(log):
    """The step of the first thermo row of log (a run continued from a restart: the restart's)."""
    lines = log.read_text(errors="replace").splitlines()
    for k, line in enumerate(lines):
        if line.split()[:1] == ["Step"]:
            for row in lines[k + 1:]:
                if row.split()[:1] and row.split()[0].isdigit():
                    return int(row.split()[0])
    return None


def compression(est_dir, nx, ny, fraction):
    """(steps of the estimate's compression, of which the loads share, whether that part was
    restored): the shared part's own run (compress/log.shear beside the estimate) when the
    checkpoint continued from it; a part restored from a committed state (its compress.restart
    without a log) counts the steps the restart was written at; else the checkpoint's steps
    before its force reached `fraction` of the smallest load (scaled to this bag's plan)."""
    state_log = est_dir / "state" / "log.shear"
    steps = runs(state_log)[0]["steps"]
    if re.search(r"^read_restart\s+\S*compress\.restart\s*$", state_log.read_text(errors="replace"), re.M):
        part_log = est_dir.parent / "compress" / "log.shear"
        if part_log.is_file():
            shared = runs(part_log)[0]["steps"]
            return steps + shared, shared, False
        shared = first_step(state_log) if (est_dir.parent / "compress" / "compress.restart").is_file() else None
        if shared:
            return steps + shared, shared, True
        raise SystemExit("project_time: %s continued from a shared part, but there is no %s"
                         % (state_log, part_log))
    lightest = min(PAPER["loads"]) * (nx - 2) * (ny - 2) / (PAPER["nx"] - 2) / (PAPER["ny"] - 2)
    return steps, min(shared_steps(state_log, fraction * lightest), steps), False


def bag_particles(nx, ny, nz):
    return nx * ny * nz - (nx - 2) * (ny - 2) * (nz - 2)


def sand_grains(nx, ny, nz, s=0.005):
    """in.fill's count: nearest to e = 0.68; the paper's 97,130 on its 81 x 81 x 17 bag."""
    if (nx, ny, nz) == (81, 81, 17):
        return 97130
    v_mean = sum(math.pi / 6 * (D_MIN + k * D_STEP) ** 3 for k in range(10)) / 10
    return round((nx - 2) * (ny - 2) * (nz - 2) * s ** 3 / ((1 + E0) * v_mean))


def measured(est_dir):
    """{ranks: the shear stretch's runs with steps} of est_dir/np<P>/log.shear."""
    found = {}
    for d in sorted(est_dir.glob("np*")):
        timed = [x for x in runs(d / "log.shear") if x["steps"] > 0]
        if timed:
            found[timed[0]["ranks"]] = timed
    if not found:
        raise SystemExit("project_time: no np*/log.shear in %s" % est_dir)
    return found


def wall_per_step(xs):
    """Wall time per step (s) over runs of one stretch."""
    return sum(x["loop"] for x in xs) / sum(x["steps"] for x in xs)


def project(est_dir, ranks, fraction):
    """The projection; fraction: of the smallest load's F_v, where the loads' shared compression ends."""
    est_dir = Path(est_dir)
    size = bag_size(est_dir, est_dir.parent)
    if size is None:
        raise SystemExit("project_time: no bag.json and no BAG line in %s" % est_dir.parent)
    nx, ny, nz = size
    fill_log = next((f for f in (est_dir / "log.fill", est_dir.parent / "log.fill") if f.is_file()),
                    est_dir.parent / "log.fill")
    restored = []    # stages a committed state made: no log here, nothing to run
    if not fill_log.is_file() and (est_dir.parent / "fill.data").is_file():
        fill_steps = 0
        restored.append("the fill")
    else:
        fill_steps = sum(x["steps"] for x in runs(fill_log))
    comp_steps, shared, part_restored = compression(est_dir, nx, ny, fraction)
    if part_restored:
        restored.append("the shared part of the compression")
    dt = timestep(est_dir / "state" / "log.shear")
    timed = measured(est_dir)
    cost = {p: wall_per_step(xs) / xs[0]["atoms"] for p, xs in timed.items()}
    atoms = bag_particles(PAPER["nx"], PAPER["ny"], PAPER["nz"]) + sand_grains(PAPER["nx"], PAPER["ny"], PAPER["nz"])
    height = (PAPER["nz"] - 2) / (nz - 2)
    comp_paper = comp_steps * height
    shared_paper = shared * height
    shear_steps = PAPER["ufinal"] / (PAPER["v"] * dt)
    steps_per_load = comp_paper - shared_paper + shear_steps
    rows = []
    pmax = max(cost)
    for p in sorted(set(cost) | {ranks}):
        c = cost[p] if p in cost else cost[pmax] * pmax / p
        rows.append((p, c, p not in cost, (fill_steps + (0 if part_restored else shared_paper)) * atoms * c / 3600,
                     steps_per_load * atoms * c / 3600))
    return dict(size=(nx, ny, nz), atoms=atoms, fill_steps=fill_steps, comp_steps=comp_steps, dt=dt,
                comp_paper=comp_paper, shared=shared, fraction=fraction, shared_paper=shared_paper, shear_steps=shear_steps,
                rows=rows, timed=timed, restored=restored)


def model(est_dir, projection):
    """The scaling model (postprocess/tbagspost/scaling.py) on the checkpoint's decomposition: costs from the 1-
    and 2-rank stretches, counts at MODEL_RANKS, checked against decomp/np<P>; None without the
    2-rank stretch or the checkpoint's data file."""
    est_dir = Path(est_dir)
    timed = projection["timed"]
    if 1 not in timed or 2 not in timed or not (est_dir / "state" / "state.data").is_file():
        return None
    data = DataFile(est_dir / "state" / "state.data")
    plates = (ZBOT, float(read_csv(est_dir / "state" / "shear.csv")["zplate_mm"][-1]) / 1000)
    owners = scaling.pair_owners(data)
    n = {p: scaling.counts(data, p, plates, owners) for p in MODEL_RANKS}

    def per_step(xs, section, k):
        return sum(x["sections"][section][k] for x in xs) / sum(x["steps"] for x in xs)

    one = {s: per_step(timed[1], s, 1) for s in timed[1][0]["sections"]}
    one["total"] = wall_per_step(timed[1])
    two = dict(Comm_min=per_step(timed[2], "Comm", 0))
    totals = dict(neigh=n[1]["neigh"].sum(), bonds=n[1]["bonds"].sum(), owned=n[1]["owned"].sum(),
                  ghosts2=n[2]["ghosts"].max())
    c = scaling.costs(one, two, totals)
    checks = {}
    for d in sorted((est_dir / "decomp").glob("np*")):
        last = runs(d / "log.shear")[-1]
        p = last["ranks"]
        counted = n[p] if p in n else scaling.counts(data, p, plates, owners)
        checks[p] = scaling.check(counted, dict(last["stats"], grid=last["grid"]))
    t1 = scaling.step_time(c, n[1], 1)
    two_measured = wall_per_step(timed[2])
    steps_total = total_steps(projection)
    rows = []
    for p in MODEL_RANKS:
        t = scaling.step_time(c, n[p], p)
        rows.append(dict(ranks=p, grid=n[p]["grid"], owned=n[p]["owned"], ghosts=n[p]["ghosts"],
                         neigh=n[p]["neigh"], bonds=n[p]["bonds"], plate=n[p]["plate"], step=t,
                         efficiency=t1 / (p * t), hours=steps_total * t * projection["atoms"] / data.x.shape[0] / 3600))
    return dict(costs=c, rows=rows, checks=checks, two_measured=two_measured,
                two_model=scaling.step_time(c, n[2], 2, dict(scaling.NETWORK, alpha=0.0, beta=0.0)))


def total_steps(r):
    """The paper run's steps: the fill, the shared part of the compression once (unless a committed
    state holds it), then per load the rest of its compression and its shear."""
    shared = 0 if "the shared part of the compression" in r.get("restored", ()) else r["shared_paper"]
    return r["fill_steps"] + shared + len(PAPER["loads"]) * (
        r["comp_paper"] - r["shared_paper"] + r["shear_steps"])


def report(r, m=None):
    nx, ny, nz = r["size"]
    out = ["Projected time of `./tbags shear paper` (81 x 81 x 17 bag, %d particles; 3 loads)" % r["atoms"],
           "measured on the %d x %d x %d bag's shear stage; steps: fill %d, compression %d x %.1f "
           "(sand height ratio) = %.0f, of which %.0f shared by the loads (run once, with the fill: "
           "to %g of the smallest load), shear %.0f per load (dt %g s)"
           % (nx, ny, nz, r["fill_steps"], r["comp_steps"], (PAPER["nz"] - 2) / (nz - 2), r["comp_paper"],
              r["shared_paper"], r["fraction"], r["shear_steps"], r["dt"]),
           "%6s %22s %22s %14s %12s" % ("ranks", "us per particle-step", "fill + shared part (h)", "per load (h)",
                                          "total (h)")]
    for p, c, extrapolated, fill_h, load_h in r["rows"]:
        out.append("%6d %20.3f%2s %22.1f %14.1f %12.1f" % (p, c * 1e6, "*" if extrapolated else "", fill_h,
                                                          load_h, fill_h + len(PAPER["loads"]) * load_h))
    if any(x[2] for x in r["rows"]):
        out.append("* extrapolated: ideal scaling from the largest measured rank count")
    if r.get("restored"):
        out.append("restored from committed states (states/), not run here: %s" % " and ".join(r["restored"]))
    if m:
        out += model_report(m)
    return "\n".join(out)


def model_report(m):
    c = m["costs"]
    out = ["", "Scaling model (tbagspost/scaling.py): per-rank counts of LAMMPS's brick decomposition of "
           "the checkpoint, costs measured here (ns): %.1f per neighbour pair, %.1f per bond, %.1f per "
           "atom (the rest), %.1f per ghost (2-rank communication); %s"
           % (c["c_pair"] * 1e9, c["c_bond"] * 1e9, c["c_atom"] * 1e9, c["c_ghost"] * 1e9, scaling.NETWORK_TEXT),
           "at 2 ranks the model (no network) gives %.2f ms per step, measured %.2f ms"
           % (m["two_model"] * 1e3, m["two_measured"] * 1e3),
           "%6s %9s %17s %17s %10s %10s %10s %9s %7s %9s" % (
               "ranks", "grid", "owned mean/max", "ghosts mean/max", "neigh max", "bonds max", "plate max",
               "ms/step", "effic.", "total (h)")]
    for row in m["rows"]:
        out.append("%6d %9s %8.0f/%-8.0f %8.0f/%-8.0f %10.0f %10.0f %10.0f %9.3f %6.0f%% %9.1f" % (
            row["ranks"], "x".join(map(str, row["grid"])), row["owned"].mean(), row["owned"].max(),
            row["ghosts"].mean(), row["ghosts"].max(), row["neigh"].max(), row["bonds"].max(),
            row["plate"].max(), row["step"] * 1e3, 100 * row["efficiency"], row["hours"]))
    below = [row["ranks"] for row in m["rows"] if row["efficiency"] < 0.5]
    out.append("efficiency falls below 50 %% at %s ranks" % below[0] if below else
               "efficiency stays above 50 %% up to %d ranks" % m["rows"][-1]["ranks"])
    for p, bad in sorted(m["checks"].items()):
        out.append("counts at %d ranks against LAMMPS's (grid, Nlocal, Nghost, Neighs; mean and max): %s"
                   % (p, "agree (means within 2 %, maxima within 5 %)" if not bad else "DIFFER: " + "; ".join(bad)))
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("estimate_dir")
    ap.add_argument("--ranks", type=int, default=1, help="also project for this many ranks")
    ap.add_argument("--shared", type=float, required=True,
                    help="the fraction of the smallest load's F_v the loads' compression shares (0: none)")
    a = ap.parse_args(argv)
    if a.ranks < 1:
        raise SystemExit("project_time: --ranks must be >= 1")
    r = project(a.estimate_dir, a.ranks, a.shared)
    text = report(r, model(a.estimate_dir, r))
    print(text)
    (Path(a.estimate_dir) / "projection.txt").write_text(text + "\n")


if __name__ == "__main__":
    sys.exit(main())
