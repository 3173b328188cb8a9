"""The command line of `./tbags shear` (python3 -m tbagsrun shear ...): arguments, set-up, then the
workflow of shear.py. `--help` prints the presets' text."""
import os
import shlex
import subprocess
import sys
import textwrap
from dataclasses import dataclass
from pathlib import Path

from . import ROOT, LaunchError
from .presets import PRESETS
from . import stages, variables
from .shear import decide, run_preset, run_realizations

USAGE = """usage: ./tbags shear [PRESET] [--realizations N] [--out DIR] [-np N (default: all cores)]
                    [--resume | --overwrite] [--loads F1960,...] [--progress SECONDS]
                    [--engine lammps|liggghts] [-var name value ...]
Bag (inputs/in.bag), fill (in.fill), simple shear (in.shear), then figures. -var values override
the preset's (any in.bag/in.fill/in.shear variable: nx ny nz, Fpaper, Fv, v, ufinal, dt, seed...).
--out DIR: write there instead of runs/<preset>/ (runs/shear-demo/ for demo).
--resume: continue an interrupted call with the same preset, -var values and --out: its bag,
fill and shared compression are reused, a run that finished is kept, and a run with a checkpoint
continues from it (in.shear's shear.restart.1/2, the newer one; in.cyclic's cyclic.restart.aK at
amplitude K + 1), its CSV keeping the rows up to the checkpoint; a run with neither starts again.
A call never removes or rewrites an earlier call's files unasked: into a folder that holds runs,
without --resume, or with --resume and other -var values, it is refused before anything runs.
--overwrite: empty the output folder first and start again (never a folder ./tbags did not make).
--loads F1960,F3730: only these of the preset's runs (by folder), their compression still the one
shared with all its loads: one load of the paper bag per job; a later call with other loads adds
them to the same folder (its bag, fill and shared compression reused). The paper preset's cost
estimate is then left out (it would cost each job about 30 min; --estimate makes one).
--progress SECONDS: a stage's progress on the console, at least this often and 10 % of the stage
apart, whichever is later, and every 10 min in a slower stage (% done and the time left measured
from the stage's rate; default 30, 0 for none).
Presets of several loads (trends, cyclic, paper) compress once to 0.9 of the smallest load's F_v
(in compress/) and continue each load from there (-var compress_to P sets the fraction, 0: each
load compresses by itself).
--realizations N: N fills of different seeds (seed, seed + 1, ...; -var seed S sets the first,
default 4821), each with the preset's shear runs, side by side where cores allow, in
runs/<preset>/r1 ... rN; then the mean curves with their spread and the table of peak S, S at
5 mm, contraction and dilatancy in runs/<preset>/realizations/ (./tbags plot --realizations).
--engine liggghts: the shear runs in LIGGGHTS with our styles (doc/liggghts.rst) from the same
LAMMPS fill (presets of shear runs: demo, trends, quasistatic), into runs/<preset>-liggghts/;
figures: S-u and w-u.
Presets:"""


def usage():
    lines = [USAGE]
    for p in PRESETS.values():
        body = textwrap.wrap(p.help + ("" if p.realizations else " (no --realizations: hours per run)"),
                             width=82)
        lines.append("  %-14s %s" % (p.name + (" (default)" if p.name == "demo" else ""), body[0]))
        lines += ["  %-14s %s" % ("", b) for b in body[1:]]
    return "\n".join(lines)


def positive(option, text, what="a positive number"):
    if not text.isdigit() or int(text) < 1:
        raise LaunchError("shear: %s needs %s" % (option, what))
    return int(text)


@dataclass
class Options:
    """./tbags shear's command line, parsed."""
    preset: object
    ranks: int
    out: object          # a Path, or None: runs/<preset>
    nreal: int           # --realizations
    estimate: bool       # --estimate: the paper's estimate only
    seed: int
    variables: dict      # -var name value(s)
    extra: list          # other words (LAMMPS switches: refused)
    engine: str
    resume: bool
    overwrite: bool
    progress_every: int  # s


def parse(argv):
    """-> the options as an Options."""
    args = list(argv)
    preset = PRESETS["demo"]
    if args and not args[0].startswith("-"):
        name = args.pop(0)
        if name not in PRESETS:
            raise LaunchError("shear: unknown preset '%s' (%s; see ./tbags shear --help)"
                              % (name, ", ".join(PRESETS)))
        preset = PRESETS[name]
    ranks, out, nreal, estimate, seed = len(os.sched_getaffinity(0)), None, 1, False, 4821
    engine, resume, overwrite, progress_every = "lammps", False, False, stages.PROGRESS_DEFAULT
    variables, extra = {}, []
    while args:
        a = args.pop(0)
        if a == "--estimate":
            if not preset.estimate:
                raise LaunchError("shear: --estimate is for the paper preset")
            estimate = True
        elif a == "--resume":
            resume = True
        elif a == "--loads":
            preset = only_loads(preset, args.pop(0) if args and not args[0].startswith("-") else "")
        elif a == "--overwrite":
            overwrite = True
        elif a == "--progress":
            text = args.pop(0) if args else ""
            if not text.isdigit():
                raise LaunchError("shear: --progress needs a whole number of seconds (0: none)")
            progress_every = int(text)
        elif a == "--engine":
            engine = args.pop(0) if args else ""
            if engine not in ("lammps", "liggghts"):
                raise LaunchError("shear: --engine must be lammps or liggghts")
        elif a == "--realizations":
            nreal = positive(a, args.pop(0) if args else "")
        elif a == "--out":
            if not args:
                raise LaunchError("shear: --out needs a directory")
            out = Path(args.pop(0)).absolute()
        elif a == "-np":
            ranks = positive(a, args.pop(0) if args else "")
        elif a == "-var":
            if not args or args[0].startswith("-"):
                raise LaunchError("shear: -var needs a name and a value")
            name = args.pop(0)
            if not args:
                raise LaunchError("shear: -var %s needs a value" % name)
            values = [args.pop(0)]    # any word, a negative number too (the checks judge it)
            while args and not is_option(args[0]):
                values.append(args.pop(0))
            if name == "seed":
                seed = positive("-var seed", values[0], "a positive integer")
            else:
                variables[name] = values if len(values) > 1 else values[0]
        elif a.startswith("--"):
            raise LaunchError("shear: unknown option %s (./tbags shear --help)" % a)
        else:    # a LAMMPS switch and its words
            extra.append(a)
            while args and not args[0].startswith("-"):
                extra.append(args.pop(0))
    if nreal > 1 and not preset.realizations:
        raise LaunchError("shear: --realizations is not for the %s preset (hours or days per "
                          "realization): run it with -var seed S and --out DIR per seed" % preset.name)
    if engine == "liggghts" and (preset.estimate or any(r.deck != "shear" for r in preset.runs)):
        raise LaunchError("shear: --engine liggghts runs the shear test only (presets demo, trends, "
                          "quasistatic); LIGGGHTS has no decks for %s yet" % preset.name)
    if engine == "liggghts" and variables.get("fabric", "solid") == "woven":
        raise LaunchError("shear: --engine liggghts offers the fabrics solid and words; woven needs "
                          "bonded bag particles that do not touch (LAMMPS's overlay/pair no): run it "
                          "in LAMMPS")
    if resume and overwrite:
        raise LaunchError("shear: --resume keeps an earlier call's runs, --overwrite removes them: give one")
    if resume and (engine != "lammps" or estimate):
        raise LaunchError("shear: --resume continues LAMMPS runs of a preset (not with --engine "
                          "liggghts or --estimate)")
    return Options(preset, ranks, out, nreal, estimate, seed, variables, extra, engine, resume,
                   overwrite, progress_every)


def only_loads(preset, text):
    """--loads F1960,F5500: the preset with those of its runs only (by folder name)."""
    names = [r.folder for r in preset.runs]
    chosen = [w for w in text.split(",") if w]
    if len(names) < 2 or not all(names):
        raise LaunchError("shear: --loads is for presets of several runs (trends, paper, cyclic ...), "
                          "not %s" % preset.name)
    unknown = [w for w in chosen if w not in names]
    if not chosen or unknown:
        raise LaunchError("shear: --loads needs some of %s, comma-separated%s"
                          % (", ".join(names), " (not %s)" % ", ".join(unknown) if unknown else ""))
    return preset.only(set(chosen))


def is_option(word):
    """A word that starts an option (-var, -np, --out ...), not a value such as -1 or -2.5e-3."""
    try:
        float(word)
        return False
    except ValueError:
        return word.startswith("-")


def set_up(liggghts=False):
    """Build the plugin if needed (./tbags setup --plugin-only; LIGGGHTS too when the runs need
    it) and take lmp's and the plugin's places from the build's tbags-env.sh."""
    subprocess.run([str(ROOT / "tbags"), "setup", "--plugin-only"] + (["--liggghts"] if liggghts else []),
                   check=True)
    build = Path(os.environ.get("TBAGS_BUILD_DIR") or ROOT / "build")
    for line in (build / "tbags-env.sh").read_text().splitlines():
        if "=" in line:
            key, value = line.split("=", 1)
            os.environ[key] = shlex.split(value)[0] if value else ""
    os.environ.setdefault("OMP_NUM_THREADS", "1")


def shear(argv):
    if argv and argv[0] in ("--help", "-h", "help"):
        print(usage())
        return
    o = parse(argv)
    if o.extra:
        raise LaunchError("shear: %s: only -var name value goes to the decks" % " ".join(o.extra))
    out = o.out or ROOT / "runs" / (o.preset.folder + ("-liggghts" if o.engine == "liggghts" else ""))
    stages.PROGRESS_EVERY = o.progress_every
    variables.check(o.preset, o.variables)    # every value, before anything is made
    if o.engine == "liggghts":
        variables.check_liggghts(o.variables)
    fabrics = () if "fabric" in o.variables else o.preset.fabrics
    for where, user in ([(out / f, dict(o.variables, fabric=f)) for f in fabrics] or [(out, o.variables)]):
        decide(o.preset, where, user, o.nreal, o.seed, o.engine, o.resume, o.overwrite, o.estimate)
    set_up(o.engine == "liggghts")

    def say(line):
        print(line, flush=True)
    if fabrics:    # a design preset: once per fabric, then compared
        for f in fabrics:
            say("tbags shear %s: fabric %s -> %s" % (o.preset.name, f, out / f))
            run_preset(o.preset, o.ranks, out / f, dict(o.variables, seed=o.seed, fabric=f), say,
                       resume=o.resume, decided=True)
        compare_fabrics(out, fabrics, say)
    elif o.nreal > 1:
        run_realizations(o.preset, o.nreal, o.seed, o.ranks, out, o.variables, say, o.engine, o.resume,
                         decided=True)
    else:
        run_preset(o.preset, o.ranks, out, dict(o.variables, seed=o.seed), say, estimate_only=o.estimate,
                   engine=o.engine, resume=o.resume, decided=True)


def compare_fabrics(out, fabrics, say):
    """fabrics.md: the design preset's isolator properties per fabric and their ratio."""
    ok, err = stages.run_python(["-m", "tbagspost.fabrics", out] +
                                ["%s=%s" % (f, out / f / "figures") for f in fabrics[:2]],
                                stdout=subprocess.DEVNULL)
    if not ok:
        raise LaunchError("%s\nshear: the fabrics' comparison failed" % err.strip())
    for line in (out / "fabrics.md").read_text().splitlines():
        say(line)


def fabric_study(argv):
    from . import fabric
    if argv and argv[0] in ("--help", "-h", "help"):
        print(fabric.USAGE)
        return
    o = fabric.parse(argv)
    variables.check(PRESETS["demo"], o.variables)
    set_up()
    fabric.run(o, lambda line: print(line, flush=True))


def main(argv):
    if not argv or argv[0] not in ("shear", "fabric"):
        sys.exit("usage: python3 -m tbagsrun shear|fabric [options] (./tbags shear --help)")
    try:
        (shear if argv[0] == "shear" else fabric_study)(argv[1:])
    except LaunchError as e:
        sys.exit("tbags: %s" % e)
    except subprocess.CalledProcessError:
        sys.exit(1)    # the set-up said why
    except KeyboardInterrupt:
        sys.exit("tbags: interrupted")
    except BrokenPipeError:    # the output piped into a reader that stopped (head)
        sys.stdout = open(os.devnull, "w")

