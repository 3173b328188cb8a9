"""./tbags fabric: what each fabric carries alone. Per fabric, the bag of inputs/in.bag filled
(in.fill) and nearly empty (in.fill -var per_size 1: ten grains), each pressed between the plates
at a constant speed (inputs/in.press: the filled bag up to twice the load, the empty one to half
its height), and the filled one on until its first bond breaks (the soilbag's compressive
strength); then postprocess/tbagspost/fabric.py: the empty bag's force at the gap where the
filled bag carries the load, as a share of the load, the curves and the walls, and the failure
load against Matsuoka and Liu's formula.
"""
import argparse
from pathlib import Path

from . import ROOT, LaunchError, guard
from .stages import run_python, stage
from .variables import CHOICES

FABRICS = CHOICES["fabric"]
USAGE = """usage: ./tbags fabric [--size NX NY NZ] [--fabrics solid,words,woven] [-np N] [--out DIR]
                     [--overwrite] [--no-strength] [-var name value ...]
Presses each fabric's bag filled and empty (ten grains) between the plates and reports the share
of the load the empty bag carries at the filled bag's gap under the load (the vertical stress of
the paper's 5.5 kN: F_v = 5500 N (nx-2)(ny-2)/79^2); then presses the filled bag on until its
first yarn bond breaks, against Matsuoka and Liu's soilbag strength (--no-strength: not). Default:
the demo bag 21 x 21 x 7, the three fabrics, 2 ranks, -> runs/fabric/ (half an hour on 2 cores;
--size 9 9 5: 4 min). -var values go to every deck (e.g. -var sand calibrated)."""


def parse(argv):
    ap = argparse.ArgumentParser(prog="./tbags fabric", usage=USAGE, add_help=False)
    ap.add_argument("--size", nargs=3, type=int, default=(21, 21, 7))
    ap.add_argument("--fabrics", default=",".join(FABRICS))
    ap.add_argument("-np", dest="ranks", type=int, default=2)
    ap.add_argument("--out", type=Path, default=ROOT / "runs" / "fabric")
    ap.add_argument("--overwrite", action="store_true")
    ap.add_argument("--no-strength", dest="strength", action="store_false")
    ap.add_argument("-var", nargs=2, action="append", default=[], metavar=("NAME", "VALUE"))
    try:
        o = ap.parse_args(argv)
    except SystemExit:
        raise LaunchError("fabric: bad arguments (above)\n" + USAGE)
    o.fabrics = o.fabrics.split(",")
    bad = [f for f in o.fabrics if f not in FABRICS]
    if bad:
        raise LaunchError("fabric: --fabrics %s: each must be %s" % (",".join(bad), " or ".join(FABRICS)))
    if min(o.size) < 3 or o.ranks < 1:
        raise LaunchError("fabric: --size needs 3 or more particles a side, -np 1 or more")
    o.variables = dict(o.var)
    if "fabric" in o.variables:
        raise LaunchError("fabric: name the fabrics with --fabrics, not -var fabric")
    if "gap_final" in o.variables:
        raise LaunchError("fabric: -var gap_final would set where every press ends; here the empty "
                          "bags are pressed to half their height, the filled ones to 2 F_v and to "
                          "their first break")
    return o


def load(nx, ny):
    """F_v (N) at the vertical stress of the paper's 5.5 kN on its 79 x 79 inner plan."""
    return 5500.0 * (nx - 2) * (ny - 2) / 79 ** 2


def run(o, say):
    out = Path(o.out)
    if out.is_dir() and any(out.iterdir()) and not o.overwrite:
        raise LaunchError("fabric: %s holds an earlier call's runs; give --overwrite to start again "
                          "(it removes its contents) or another --out. Nothing was changed." % out)
    guard.make(out, empty=o.overwrite)
    nx, ny, nz = o.size
    size = dict(nx=nx, ny=ny, nz=nz)
    Fv = load(nx, ny)
    stage(out, "bag", o.ranks, dict(size, **o.variables), say)
    folders = {}
    for fabric in o.fabrics:
        both = {}
        for kind, fill_vars, press_vars in (("filled", {}, dict(Fstop=2 * Fv)), ("empty", dict(per_size=1), {})):
            folder = out / fabric / kind
            folder.mkdir(parents=True, exist_ok=True)
            common = dict(size, fabric=fabric, **o.variables)
            stage(folder, "fill", o.ranks, dict(common, bag="../../bag.data", **fill_vars), say)
            stage(folder, "press", o.ranks, dict(common, **press_vars), say)
            both[kind] = folder
        folders[fabric] = (both["empty"], both["filled"])
        if o.strength:    # the filled bag pressed on until its first bond breaks
            folder = out / fabric / "strength"
            folder.mkdir(parents=True, exist_ok=True)
            stage(folder, "press", o.ranks, dict(size, fabric=fabric, fill="../filled/fill.data", until_break=1,
                                                 gap_final=0.3, **o.variables), say)
    args = ["-m", "tbagspost.fabric", out, "--Fv", Fv, "--size", nx, ny, nz,
            "--sand", o.variables.get("sand", "paper")] + [
        x for f in o.fabrics for x in ("--pair", f, folders[f][0], folders[f][1])]
    if o.strength:
        args += [x for f in o.fabrics for x in ("--strength", f, out / f / "strength")]
    with open(out / "fabric-alone.txt", "w") as fh:
        ok, err = run_python(args, stdout=fh)
    if not ok:
        raise LaunchError("%s\nfabric: the report failed" % err.strip())
    for line in (out / "fabric-alone.txt").read_text().splitlines():
        say(line)
