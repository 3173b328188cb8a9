"""The shear presets' workflow (the presets are data in presets.py).

One realization: the bag (inputs/in.bag) and its fill (in.fill) in the output folder, then the
preset's runs from that fill (side by side, the ranks shared, or one after the other), each a
LAMMPS stage with its log (log.<deck>) and screen output (screen.<deck>.txt) in its folder; then
the figures (postprocess/tbagspost) and the preset's checks (tbagspost/check_trends.py).
Realizations: the same with fills of seeds S, S + 1, ... in r1, r2, ..., as many at once as the
cores allow, then their spread (tbagspost --realizations).
The paper preset first measures a short stretch of its own bag and projects its time and its
scaling over ranks (estimate.py). engine "liggghts": the shear runs in LIGGGHTS instead
(liggghts_stage.py). One stage, its reuse and its --resume: stages.py.
"""
import os
import re
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from . import LaunchError, guard
from .estimate import estimate_paper
from .liggghts_stage import stage_liggghts
from .presets import COMPRESS_SHARED, Run
from .resume import past_start
from .stages import run_module, run_python, stage_once, stage_run, vars_key


def side_by_side(jobs, say):
    """Run the callables jobs[k](say) at once; each one's lines are said together, in order, when
    all have finished; stops if one failed."""
    buffers = [[] for _ in jobs]
    with ThreadPoolExecutor(len(jobs)) as pool:
        futures = [pool.submit(job, buf.append) for job, buf in zip(jobs, buffers)]
    failed = []
    for fut, buf in zip(futures, buffers):
        for line in buf:
            say(line)
        if fut.exception() is not None:
            if not isinstance(fut.exception(), LaunchError):
                raise fut.exception()
            say(str(fut.exception()))
            failed.append(fut.exception())
    if failed:
        raise LaunchError("shear: %d of %d runs failed (above)" % (len(failed), len(jobs)))


def run_folder(out, run):
    return Path(out) / run.folder if run.folder else Path(out)


def run_variables(preset, run, user):
    """A run's -var values: the bag's size, the run's own, the fill from the folder above for a
    run in a subfolder, then the user's (which win)."""
    variables = dict(preset.bag, **run.variables)
    if run.folder:
        variables["fill"] = "../fill.data"
    variables.update(user)
    return variables


# the -var values of the decks' motion after the compression (in.shear's shear, in.cyclic's
# cycles and histories), which the shared part of the compression does not read: left out of the
# part's variables, so that the part (and its committed state) serves runs of any speed and length
MOTION = {"v", "ufinal", "du_csv", "du_dump", "steps", "trace", "state", "amps", "cycles", "wave",
          "vpeak", "rows", "start", "hrow", "hchunks", "history"}


def part_variables(preset, part, user):
    """The shared part's -var values: run_variables() without the motion's (MOTION)."""
    return {k: v for k, v in run_variables(preset, part, user).items() if k not in MOTION}


def shared_compression(preset, user, engine):
    """The run that makes the compression's shared part (folder "compress", the smallest load,
    -var compress_to: COMPRESS_SHARED or the user's fraction, 0 for none), when the preset's runs
    (all of them: compress_runs under --loads) differ only in their load (Fpaper) and compress
    fresh in LAMMPS; else None."""
    runs = preset.compress_runs or preset.runs
    fraction = float(user.get("compress_to", COMPRESS_SHARED))
    if engine != "lammps" or len(runs) < 2 or len({r.deck for r in runs}) > 1 or fraction <= 0 or \
            {"restart", "compress_from"} & set(user):
        return None
    rest = [{k: v for k, v in r.variables.items() if k != "Fpaper"} for r in runs]
    if any(x != rest[0] for x in rest) or any("Fpaper" not in r.variables for r in runs):
        return None
    lightest = min(runs, key=lambda r: r.variables["Fpaper"])
    return Run("compress", lightest.deck, dict(lightest.variables, compress_to=fraction))    # see part_variables


def plan(preset, out, user, engine="lammps"):
    """Every stage of one realization in `out`, in the order they run (guard.Stage): the bag and
    the fill, the loads' shared start of compression (if the preset has one), then its runs with
    the variables each gets."""
    out = Path(out)
    fill_vars = dict(preset.bag, **user)
    stages = [guard.Stage(out, "bag", fill_vars, "bag.data"), guard.Stage(out, "fill", fill_vars, "fill.data")]
    part = shared_compression(preset, user, engine)
    each_user = user
    if part:
        folder = run_folder(out, part)
        stages.append(guard.Stage(folder, part.deck, part_variables(preset, part, user), "compress.restart"))
        each_user = {k: v for k, v in user.items() if k != "compress_to"}    # the part's only
        each_user["compress_from"] = os.path.relpath(folder / "compress.restart", run_folder(out, preset.runs[0]))
    for run in preset.runs:
        stages.append(guard.Stage(run_folder(out, run), run.deck, run_variables(preset, run, each_user)))
    return stages


def realization(preset, out, user, engine="lammps"):
    """(plan's stages, the fill's stamp) of one realization: what guard.check compares."""
    return plan(preset, out, user, engine), vars_key(dict(preset.bag, **user))


def check_realization(out, stages, origin, resume, overwrite, estimate_only=False):
    """guard.check of one realization (--estimate makes no runs: its bag, fill and compression
    only)."""
    guard.check(out, [([s for s in stages if s.product] if estimate_only else stages, origin)],
                resume, overwrite)


def decide(preset, out, user, nreal=1, seed=4821, engine="lammps", resume=False, overwrite=False,
           estimate_only=False):
    """What the call does to `out`, decided before anything runs (guard.check): refused if it
    would remove or rewrite an earlier call's files, `out` emptied first with overwrite."""
    out = Path(out)
    if nreal > 1:
        groups = [realization(preset, out / ("r%d" % k), dict(user, seed=seed + k - 1), engine)
                  for k in range(1, nreal + 1)]
        guard.check(out, groups, resume, overwrite)
    else:
        check_realization(out, *realization(preset, out, dict({"seed": seed}, **user), engine), resume,
                          overwrite, estimate_only)    # (a seed among the user's values wins)


def estimate_load(preset, user):
    """The load the estimate's short shear runs at: that of the preset's first run, unless the
    user gave one (with --loads F1960, 1.96 kN: a few thousand steps past the shared compression,
    where it compressed the paper bag on to in.shear's default 5.50 kN for the timing alone)."""
    first = preset.runs[0].variables if preset.runs else {}
    return {k: first[k] for k in ("Fpaper", "Fv") if k in first and k not in user}


def skip_estimate(preset, runs, resume, estimate_only):
    """Why a preset with an estimate (paper) makes none in this call, or "": not when --loads picks
    its loads (one per job: the estimate's own compression and timing cost about 30 min of each
    job), nor when --resume finds every run past its start."""
    if not preset.estimate or estimate_only:
        return ""
    if preset.compress_runs:
        return "--loads %s" % ",".join(r.folder for r in preset.runs)
    if resume and past_start(runs):
        return "every run continues from its checkpoint (or finished)"
    return ""


def run_preset(preset, ranks, out, user, say, estimate_only=False, in_realizations=False,
               engine="lammps", resume=False, overwrite=False, decided=False):
    """One realization of a preset into `out`; user: the -var values given (they win); engine:
    where the shear runs go (the bag and the fill are LAMMPS's); resume: continue the runs of an
    earlier call in `out` (stage_run), its bag, fill and shared compression reused; overwrite:
    empty `out` first. Decided before any stage runs (guard.check): a call that would remove or
    rewrite an earlier call's files is refused (decided: the caller did it, decide())."""
    t0 = time.time()
    out = Path(out)
    fill_vars = dict(preset.bag, **user)
    stages, origin = realization(preset, out, user, engine)    # origin: a run resumes on the same fill
    if not (decided or in_realizations):
        check_realization(out, stages, origin, resume, overwrite, estimate_only)
    guard.make(out)
    (bag, fill, *part), runs = [s for s in stages if s.product], [s for s in stages if not s.product]
    part_stage = part and (part[0].folder, part[0].deck, ranks, part[0].variables, say, part[0].product)
    why_not = skip_estimate(preset, runs, resume, estimate_only)
    if why_not:
        say("tbags shear %s: %s: no estimate made (./tbags shear %s --estimate makes one)"
            % (preset.name, why_not, preset.name))
    elif preset.estimate:
        estimate_paper(out, fill_vars, ranks, say, part_stage, resume and not estimate_only,
                       estimate_load(preset, user))
        if estimate_only:
            return
    for name, line in preset.defaults_said.items():
        if name not in user:
            say("tbags shear %s: %s" % (preset.name, line))
    stage_once(out, "bag", ranks, bag.variables, say, bag.product)
    stage_once(out, "fill", ranks, fill.variables, say, fill.product)
    if part_stage:
        stage_once(*part_stage)

    def job(run, stage, r):
        if engine == "liggghts":
            return lambda s: stage_liggghts(stage.folder, r, stage.variables, s)
        return lambda s: stage_run(stage.folder, stage.deck, r, stage.variables, s, resume, origin)

    if preset.side_by_side and len(preset.runs) > 1:
        each = max(1, ranks // len(preset.runs))
        say("tbags shear: %s side by side, %d rank(s) each ..."
            % (", ".join(r.folder for r in preset.runs), each))
        side_by_side([job(r, st, each) for r, st in zip(preset.runs, runs)], say)
    else:
        for r, st in zip(preset.runs, runs):
            job(r, st, ranks)(say)
    post_process(preset, out, say, engine)
    check(preset, out, say, in_realizations)
    say("tbags shear %s: done in %d s. Outputs in %s:" % (preset.name, time.time() - t0, out))
    files = [p for p in list(out.glob("*")) + list(out.glob("*/*")) if p.is_file() and not p.name.startswith("dump.")]
    for p in sorted(files):
        say("  %s" % p)
    say("  + %d dump files (dump.grains.*, dump.contacts.*, dump.bonds.*, *.vtp; every 1 mm of u)"
        % len(list(out.rglob("dump.*"))))


def post_process(preset, out, say, engine="lammps"):
    runs = [run_folder(out, r) for r in preset.runs]
    with open(out / "figures.txt", "w") as fh:
        if engine == "liggghts":    # no dumps from LIGGGHTS yet: S-u and w-u
            ok, err = run_python(["-m", "tbagspost"] + runs + ["--only", "shear"], fh)
        elif preset.post == "figures":
            ok, err = run_python(["-m", "tbagspost"] + runs + ["--vtk"], fh)
        elif preset.post == "cyclic":
            ok, err = run_python(["-m", "tbagspost"] + runs, fh)
        else:    # stack: the single bag and the stack
            ok, err = run_python(["-m", "tbagspost"] + runs + ["-o", out / "figures"], fh)
    if not ok:
        raise LaunchError("%s\nshear: post-processing failed (./tbags plot %s)"
                          % (err.strip(), " ".join(str(r) for r in runs)))
    if engine == "liggghts":
        say("tbags shear: S-u and w-u in RUN/figures/shear.png; the numbers: %s/figures.txt" % out)
    elif preset.post == "figures":
        say("tbags shear: figures in RUN/figures/ (S-u and w-u, deformed shape, contact network%s),"
            % (", and %s/figures/shear-overlay.png" % out if len(runs) > 1 else ""))
        say("  ParaView series in RUN/paraview/*.pvd; the numbers behind the figures: %s/figures.txt" % out)
    else:
        report = (out / "figures" / "report.md").read_text().splitlines()
        head = "## Ramberg" if preset.post == "cyclic" else "## Stack"
        start = next((k for k, line in enumerate(report) if line.startswith(head)), len(report))
        for line in report[start:]:
            if not line.startswith("wrote"):
                say(line)


STUDIES = ("rate", "protocol")    # checks that compare a preset's runs over its realizations


def study(preset, out, say):
    """tbagspost.rate or .protocol over the variant folders of out (its realizations' or its own)."""
    if not run_module(preset.check, [out], say)[0]:
        raise LaunchError("%s: the study failed (above)" % preset.check)


def check(preset, out, say, in_realizations):
    if preset.check in STUDIES:    # over the realizations when there are several
        if not in_realizations:
            study(preset, out, say)
        return
    if not preset.check:
        return
    args = [out] if preset.check == "trends" else ["--speed"] + [run_folder(out, r) for r in preset.runs]
    ok, _ = run_module("check_trends", args, say)
    if not ok:
        if preset.check == "speed":
            raise LaunchError("quasistatic: the S-u curves differ (above)")
        if not in_realizations:    # in realizations, the summary's check decides
            raise LaunchError("trends: a finding did not hold (above)")


def run_realizations(preset, n, seed, ranks, out, user, say, engine="lammps", resume=False,
                     overwrite=False, decided=False):
    """n realizations of a preset (fills of seeds seed, seed + 1, ...) in out/r1 ... out/rn, as
    many at once as the cores allow, then their spread in out/realizations; resume, overwrite:
    as run_preset's, decided for all realizations before any runs."""
    t0 = time.time()
    out = Path(out)
    if not decided:
        decide(preset, out, user, n, seed, engine, resume, overwrite)
    per = len(preset.runs) if preset.side_by_side else 1    # runs of one realization at once
    slots = min(max(1, ranks // per), n)
    each = max(1, ranks // slots)
    say("tbags shear %s: %d realizations (seeds %d to %d), %d at a time with %d rank(s) each ..."
        % (preset.name, n, seed, seed + n - 1, slots, each))

    def one(k):
        with open(out / ("r%d.log" % k), "w") as log:
            def say_k(line):
                print(line, file=log, flush=True)
            try:
                run_preset(preset, each, out / ("r%d" % k), dict(user, seed=seed + k - 1), say_k,
                           in_realizations=True, engine=engine, resume=resume)
            except LaunchError as e:
                say_k("tbags: %s" % e)
                return False
        say("  realization r%d done (%d s)" % (k, time.time() - t0))
        return True

    with ThreadPoolExecutor(slots) as pool:
        ok = list(pool.map(one, range(1, n + 1)))
    for k in range(1, n + 1):
        say("-- r%d:" % k)
        for line in (out / ("r%d.log" % k)).read_text().splitlines():
            if re.match(r"^  (FILL |SHEARED|COMPRESSED)", line) or "check" in line:
                say(line)
    if not all(ok):
        raise LaunchError("shear: a realization failed (its log: %s/r*.log)" % out)
    runs = [run_folder(out / ("r%d" % k), r) for k in range(1, n + 1) for r in preset.runs]
    ok, err = run_python(["-m", "tbagspost"] + runs + ["--only", "none", "--realizations", "-o",
                                                   out / "realizations"])
    if not ok:
        raise LaunchError("%s\nshear: the realizations' summary failed" % err.strip())
    say("tbags shear %s: %d realizations done in %d s; spread in %s/realizations/"
        % (preset.name, n, time.time() - t0, out))
    if preset.check in STUDIES:
        study(preset, out, say)
    if preset.check == "trends":
        ok, text = run_module("check_trends", [out], say)
        (out / "realizations" / "check.txt").write_text(text)
        if not ok:
            raise LaunchError("trends: a finding did not hold in a realization (above; "
                              "%s/realizations/check.txt)" % out)
