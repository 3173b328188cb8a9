"""The paper preset's estimate (./tbags shear paper --estimate): its run's cost measured on its own
bag, projected over the whole run and over rank counts (postprocess/tbagspost: project_time.py, scaling.py).
"""
import os
import shutil
from pathlib import Path

from . import LaunchError, resume, use_postprocess
from .presets import DECOMPOSITIONS, ESTIMATE
from .stages import made_part, run_module, stage, stage_once


def estimate_paper(out, fill_vars, ranks, say, part=None, reuse=False, load=None):
    """The paper run's cost measured on its own bag (fill_vars: its size and the user's -var
    values): the bag and its fill (the run's own, in out), the loads' shared part of the
    compression (part: stage_once's arguments, in out/compress; the run's loads reuse it), the
    rest of the compression and a short shear to a checkpoint (estimate/state), each made once; then a short
    stretch resumed from the checkpoint at 1, 2 and `ranks` ranks (estimate/np<P>) and a few steps
    at each of DECOMPOSITIONS ranks (estimate/decomp/np<P>: LAMMPS's own decomposition, for the
    scaling model); then the projection (tbagspost/project_time.py). reuse: an earlier projection
    is said again instead of timing anew. load: the shear's load variables (Fpaper, Fv), its
    stages only (the bag's and fill's stamps stay those of the run)."""
    use_postprocess()
    from tbagspost.run import log_timestep    # the decks' TIMESTEP line (numpy: after set-up)
    counts = [1] + ([2] if ranks >= 2 else []) + ([ranks] if 2 < ranks <= os.cpu_count() else [])
    folder = Path(out) / "estimate"
    stage_once(out, "bag", ranks, fill_vars, say, "bag.data")
    stage_once(out, "fill", ranks, fill_vars, say, "fill.data")
    e = ESTIMATE
    shear = dict(fill_vars, **(load or {}), v=e["v"], du_csv=e["du_csv"])
    state = dict(shear, fill="../../fill.data", ufinal=e["u_state"], du_dump=e["u_state"], state=1)
    if part:
        state["compress_from"] = made_part(part, folder / "state")
    stage_once(folder / "state", "shear", ranks, state, say, "state.data")
    projection = folder / "projection.txt"
    if reuse and projection.is_file():
        say("tbags shear paper: the estimate in %s, made before (./tbags shear paper --estimate "
            "measures it again):" % projection)
        for line in projection.read_text().splitlines()[:5]:
            say(line)
        return
    restart = resume.checkpoints(folder / "state", "shear")[0][0]    # the newer
    timed = round(e["u_timed"] / (e["v"] * float(log_timestep(folder / "state" / "log.shear"))))
    say("tbags shear paper: timing %d shear steps of the paper bag at %s rank(s) ..."
        % (timed, " and ".join(map(str, counts))))
    quiet = lambda line: None    # noqa: E731
    for r in counts:
        sub = folder / ("np%d" % r)
        shutil.rmtree(sub, ignore_errors=True)
        stage(sub, "shear", r, dict(shear, restart="../state/" + restart, steps=timed, du_dump=1), quiet)
    say("tbags shear paper: the domain decomposition at %s ranks (a few steps each) ..."
        % " ".join(map(str, DECOMPOSITIONS)))
    for r in DECOMPOSITIONS:
        sub = folder / "decomp" / ("np%d" % r)
        shutil.rmtree(sub, ignore_errors=True)
        stage(sub, "shear", r, dict(shear, restart="../../state/" + restart, steps=5, du_dump=1), quiet)
    shared = part[3]["compress_to"] if part else 0    # where the loads' shared compression ends
    if not run_module("project_time", [folder, "--ranks", ranks, "--shared", shared], say)[0]:
        raise LaunchError("paper: the projection failed (above)")
