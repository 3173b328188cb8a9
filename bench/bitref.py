#!/usr/bin/env python3
"""The bits of the contact law, for a refactor that must not change them: 31 short runs that go
through every path of pair gran/hertz/rolling and fix wall/gran/servo (rolling epsd, cdt and
none; newton on and off; the AVX2 and baseline kernels; rolling_radius mean; limit_damping; special-bond
weights; frozen atoms; single() through compute pair/local; 2 ranks; the plates' explicit and
implicit damping on the tiny bag), each reduced to the sha256 of what it writes at %.17g
(forces, torques, velocities, thermo, every step's plate values).

  set -a; . build/tbags-env.sh; set +a
  /usr/bin/python3 bench/bitref.py --save /tmp/before.txt     (on the code before the change)
  /usr/bin/python3 bench/bitref.py --check /tmp/before.txt    (after: lists every run that moved)

The references depend on the compiler and the machine's AVX2, so they are compared on one machine,
not committed.
"""
import argparse
import hashlib
import re
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "decks"))
import lmprun  # noqa: E402
import packing  # noqa: E402
import test_pair_kernel as kernel  # noqa: E402
import test_pair_special as special  # noqa: E402

THERMO = re.compile(r"^\s*\d+(\s+\S+){4}\s*$")
SINGLE = lmprun.packing_head() + """pair_style gran/hertz/rolling ${model} ${options}
pair_coeff 1 1 material 1.8e9 0.1 friction 0.31 rolling 0.05 restitution 0.2
pair_coeff 2 2 material 0.75e9 0.1 friction 0.26 rolling 0.03 restitution 0.3
pair_coeff 1 2 friction 0.2 rolling 0.04 restitution 0.25
variable vx atom 0.05*normal(0,1,4929)
variable vy atom 0.05*normal(0,1,4930)
variable vz atom 0.05*normal(0,1,4931)
velocity all set v_vx v_vy v_vz
timestep 1e-6
fix 1 all nve/sphere
run 100
""" + lmprun.CONTACT_DUMP


def digest(folder, names, log_thermo=True):
    h = hashlib.sha256()
    for n in names:
        h.update((Path(folder) / n).read_bytes())
    if log_thermo:
        lines = [l for l in (Path(folder) / "log.lammps").read_text().splitlines() if THERMO.match(l)]
        h.update("\n".join(lines).encode())
    return h.hexdigest()


def runs(tmp):
    """[(name, sha256)] of every run."""
    data = packing.make(tmp / "packing")
    out = []

    def one(name, deck, variables, files, np_ranks=1, thermo=True):
        wd = tmp / name
        lmprun.run(deck, wd, np_ranks=np_ranks, variables=variables).check()
        out.append((name, digest(wd, files, thermo)))
        print("%-40s %s" % (name, out[-1][1][:16]), flush=True)

    for model in ("epsd", "cdt", "none"):
        for newton in ("on", "off"):
            for opt in ("", "kernel baseline"):
                one("kernel-%s-newton%s%s" % (model, newton, "-baseline" if opt else ""), kernel.DECK,
                    {"data": data, "model": model, "newton": newton, "options": opt}, ["final.dump"])
    for model in ("epsd", "cdt"):
        one("kernel-%s-rolling_radius_mean" % model, kernel.DECK,
            {"data": data, "model": model, "newton": "on", "options": "rolling_radius mean"}, ["final.dump"])
    one("kernel-epsd-limit_damping", kernel.DECK,
        {"data": data, "model": "epsd", "newton": "on", "options": "limit_damping"}, ["final.dump"])
    for model in ("epsd", "cdt", "none"):
        for newton in ("on", "off"):
            one("kernel-%s-newton%s-2ranks" % (model, newton), kernel.DECK,
                {"data": data, "model": model, "newton": newton, "options": ""}, ["final.dump"], np_ranks=2)
    for model in ("epsd", "cdt", "none"):
        one("single-%s" % model, SINGLE, {"data": data, "model": model, "options": ""},
            ["contacts.dump", "forces.dump"], thermo=False)
    one("freeze-epsd", kernel.FREEZE, {"data": data}, ["contacts.dump", "forces.dump"], thermo=False)
    for w in (0.5, 1):
        for opt in ("", "kernel baseline"):
            wd = tmp / ("special-w%g%s" % (w, "-baseline" if opt else ""))
            res = lmprun.run(special.DECK, wd, variables={"w": w, "options": opt, "nsteps": 200}).check()
            lines = "\n".join(l for l in res.output.splitlines() if l.startswith(("F1 ", "F2 ")))
            out.append((wd.name, hashlib.sha256(lines.encode()).hexdigest()))
            print("%-40s %s" % (wd.name, out[-1][1][:16]), flush=True)
    fill = lmprun.filled_bag(tmp / "tiny")
    for damping in ("explicit", "implicit"):
        v = dict(lmprun.TINY_BAG, fill="../tiny/fill.data", damping=damping, trace=1, v=0.02, ufinal=0.0002)
        one("tiny-shear-%s" % damping, lmprun.INPUTS / "in.shear", v, ["shear.steps.csv", "shear.csv"],
            thermo=False)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    g = ap.add_mutually_exclusive_group(required=True)
    g.add_argument("--save", type=Path, help="write the runs' sha256 here")
    g.add_argument("--check", type=Path, help="compare the runs' sha256 with this file")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory(prefix="bitref-") as tmp:
        got = runs(Path(tmp))
    text = "".join("%s %s\n" % r for r in got)
    if args.save:
        args.save.write_text(text)
        print("%d runs saved to %s" % (len(got), args.save))
        return 0
    ref = dict(l.split() for l in args.check.read_text().splitlines())
    moved = [n for n, h in got if ref.get(n) != h]
    print("%d runs, %d bit-identical to %s%s" % (len(got), len(got) - len(moved), args.check,
                                                  "; moved: " + ", ".join(moved) if moved else ""))
    return 1 if moved else 0


if __name__ == "__main__":
    sys.exit(main())
