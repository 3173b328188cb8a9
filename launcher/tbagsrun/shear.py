"""The shear presets' workflow (the presets are data in presets.py).

One realization: the bag (inputs/in.bag) and its fill (in.fill) in the output folder, then the
preset's runs from that fill (side by side, the ranks shared, or one after the other), each a
LAMMPS stage with its log (log.<deck>) and screen output (screen.<deck>.txt) in its folder; then
the figures (postprocess/tbagspost) and the preset's checks (inputs/check_trends.py).
Realizations: the same with fills of seeds S, S + 1, ... in r1, r2, ..., as many at once as the
cores allow, then their spread (tbagspost --realizations).
The paper preset first measures a short stretch of its own bag and projects its time and its
scaling over ranks (inputs/project_time.py, inputs/scaling.py).
engine "liggghts": the shear runs in LIGGGHTS instead (inputs/liggghts/in.shear on the LAMMPS
fill converted), written to the same shear.csv columns; figures: S-u and w-u.
"""
import json
import os
import re
import shutil
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from . import ROOT, LaunchError, lammps, progress, resume as resumed
from .presets import COMPRESS_SHARED, DECOMPOSITIONS, ESTIMATE, Run

sys.path.insert(0, str(ROOT / "postprocess"))
from tbagspost.run import log_timestep  # noqa: E402  (the reader of the decks' TIMESTEP line)

# the lines of a stage's screen output that the launcher repeats (the decks' summaries)
SUMMARY = re.compile(r"^(BAG|FILL|TIMESTEP|INERTIAL|COMPRESSION PART|COMPRESSED|SHEARED|CYCLIC|CYCLED|AMPLITUDE [0-9]+ DONE)")
MARKER = ".tbags-run"    # in every output folder the launcher made (so --out never clears a user's)
PROGRESS_DEFAULT = 600    # s between a stage's progress lines on the console (--progress; 0: none)
PROGRESS_EVERY = PROGRESS_DEFAULT


def run_python(args, stdout=None):
    """Debian's Python on a module or script of the repository, postprocess/ on its path."""
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        [str(ROOT / "postprocess")] + ([os.environ["PYTHONPATH"]] if os.environ.get("PYTHONPATH") else [])))
    proc = subprocess.run([sys.executable] + [str(a) for a in args], env=env, stdout=stdout,
                          stderr=subprocess.PIPE, text=True)
    return proc.returncode == 0, proc.stderr


def run_script(name, args, say):
    """inputs/<name> (a check or a projection) on args; says its output; (succeeded, stdout)."""
    proc = subprocess.run([sys.executable, ROOT / "inputs" / name] + [str(a) for a in args],
                          capture_output=True, text=True)
    for line in (proc.stdout + proc.stderr).splitlines():
        say(line)
    return proc.returncode == 0, proc.stdout


def stage(folder, deck, ranks, variables, say):
    """inputs/in.<deck> in folder with `ranks` ranks; says its summary lines; stops if it fails.
    Its progress goes to the console every PROGRESS_EVERY seconds (progress.py)."""
    say("tbags shear: %s in %s ..." % (deck, folder))
    screen = "screen.%s.txt" % deck
    with progress.Watch(Path(folder) / screen, "%s in %s" % (deck, folder), PROGRESS_EVERY,
                        lambda line: print(line, flush=True)):
        res = lammps.run(ROOT / "inputs" / ("in." + deck), folder, ranks, variables,
                         log="log." + deck, screen=screen)
    report(res, "the %s stage" % deck, Path(folder) / ("log." + deck), say)


def report(res, what, log, say):
    """A finished stage: its summary lines said, or LaunchError with its ERROR lines (else its
    output's end) when it failed."""
    lines = res.output.splitlines()
    if res.returncode != 0:
        errors = [line for line in lines if "ERROR" in line] or lines[-20:]
        raise LaunchError("\n".join(errors) + "\nshear: %s failed (see %s)" % (what, log))
    for line in lines:
        if SUMMARY.match(line):
            say("  " + line)


def stage_liggghts(folder, ranks, variables, say):
    """inputs/liggghts/in.shear in folder: the run's LAMMPS fill converted (convert_fill.py), then
    LIGGGHTS on `ranks` ranks (split across x, through the bag), then shear.csv (in.shear's
    columns) from its means and per-step trace (deleted unless -var trace 1); stops if it
    fails."""
    folder = Path(folder)
    say("tbags shear: shear (LIGGGHTS) in %s ..." % folder)
    ok, err = run_python([ROOT / "inputs" / "liggghts" / "convert_fill.py",
                          folder / str(variables.get("fill", "fill.data")), folder / "fill.liggghts.data"],
                         stdout=subprocess.DEVNULL)
    if not ok:
        raise LaunchError("%s\nshear: could not convert the fill for LIGGGHTS" % err.strip())
    res = lammps.run(ROOT / "inputs" / "liggghts" / "in.shear", folder, ranks,
                     dict(variables, fill="fill.liggghts.data", procs="%d 1 1" % ranks),
                     log="log.shear", screen="screen.shear.txt", engine="liggghts")
    report(res, "the LIGGGHTS shear", folder / "log.shear", say)
    means_to_csv(folder / "shear.means.txt", folder / "shear.csv", folder / "shear.start.txt",
                 folder / "shear.steps.txt")
    if str(variables.get("trace", 0)) != "1":    # -var trace 1 keeps it, as in.shear's trace
        (folder / "shear.steps.txt").unlink()


# inputs/in.shear's CSV columns, which the LIGGGHTS run's CSV gives too
SHEAR_CSV = ("time_s,u_mm,w_mm,S_N,Fv_N,broken_bonds,zplate_mm,steps,w_min_mm,w_max_mm,S_min_N,S_max_N,"
             "Fv_min_N,Fv_max_N,zplate_min_mm,zplate_max_mm")


def means_to_csv(means, csv, start, steps):
    """inputs/liggghts/in.shear's outputs (SI) as the shear CSV of inputs/in.shear (mm, N):
    fix ave/time's means (step t u w S F_v z_plate), after the row at u = 0 of `start`
    (shear.start.txt: one step, as LAMMPS's first row); the min and max of w, S, F_v and z_plate
    over each row's interval of steps, and the broken bonds at its last step, from the per-step
    trace `steps` (shear.steps.txt: step w S F_v z_plate broken). Stops if the trace does not
    cover every step of every row."""
    def table(path):
        return [[float(x) for x in line.split()] for line in Path(path).read_text().splitlines()
                if line.strip() and not line.startswith("#")]

    def row(t, u, w, S, F, broken, z, nsteps, lows, highs):
        """a CSV row: means (SI in, mm and N out), then min and max of w, S, F_v and z_plate"""
        scale = (1e3, 1.0, 1.0, 1e3)
        ext = [x * k for lo, hi, k in zip(lows, highs, scale) for x in (lo, hi)]
        return ",".join(["%.7f" % t] + ["%.4f" % x for x in (u * 1e3, w * 1e3, S, F)]
                        + ["%d" % broken, "%.4f" % (z * 1e3), "%d" % nsteps] + ["%.4f" % x for x in ext])

    out = [SHEAR_CSV, "# LIGGGHTS (inputs/liggghts/in.shear): means over each row's interval of steps "
           "(min, max beside); broken bonds since the compressed state"]
    t, u, w, S, F, z = table(start)[0][1:7]
    out.append(row(t, u, w, S, F, 0, z, 1, (w, S, F, z), (w, S, F, z)))
    trace = table(steps)
    k = last = 0
    for step, t, u, w, S, F, z in (r[:7] for r in table(means)):
        chunk = []    # the trace's rows of the steps last+1 .. step
        while k < len(trace) and trace[k][0] <= step:
            if trace[k][0] > last:
                chunk.append(trace[k])
            k += 1
        if len(chunk) != step - last:
            raise LaunchError("shear: %s has %d of the %d steps %d-%d of a row of %s" %
                              (steps, len(chunk), step - last, last + 1, step, means))
        cols = list(zip(*chunk))[1:5]    # w S F_v z_plate
        out.append(row(t, u, w, S, F, chunk[-1][5], z, step - last, map(min, cols), map(max, cols)))
        last = step
    Path(csv).write_text("\n".join(out) + "\n")


def fresh_dir(folder):
    """An empty folder for a run's outputs. A non-empty folder outside runs/ must be one the
    launcher made (its marker), so that --out never clears a folder of the user's."""
    folder = Path(folder)
    if folder.is_dir() and any(folder.iterdir()) and not (folder / MARKER).exists() and \
            (ROOT / "runs") not in folder.resolve().parents:
        raise LaunchError("shear: %s is not empty and was not made by ./tbags shear; choose another "
                          "--out" % folder)
    shutil.rmtree(folder, ignore_errors=True)
    folder.mkdir(parents=True)
    (folder / MARKER).touch()


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


def shared_compression(preset, user, engine):
    """The run that makes the compression's shared part (folder "compress", the smallest load,
    -var compress_to: COMPRESS_SHARED or the user's fraction, 0 for none), when the preset's runs
    differ only in their load (Fpaper) and compress fresh in LAMMPS; else None."""
    runs = preset.runs
    fraction = float(user.get("compress_to", COMPRESS_SHARED))
    if engine != "lammps" or len(runs) < 2 or len({r.deck for r in runs}) > 1 or fraction <= 0 or \
            {"restart", "compress_from"} & set(user):
        return None
    rest = [{k: v for k, v in r.variables.items() if k != "Fpaper"} for r in runs]
    if any(x != rest[0] for x in rest) or any("Fpaper" not in r.variables for r in runs):
        return None
    lightest = min(runs, key=lambda r: r.variables["Fpaper"])
    return Run("compress", lightest.deck, dict(lightest.variables, compress_to=fraction))


def run_preset(preset, ranks, out, user, say, estimate_only=False, in_realizations=False,
               engine="lammps", resume=False):
    """One realization of a preset into `out`; user: the -var values given (they win); engine:
    where the shear runs go (the bag and the fill are LAMMPS's); resume: continue the runs of an
    earlier call in `out` (stage_run), its bag, fill and shared compression reused."""
    t0 = time.time()
    out = Path(out)
    fill_vars = dict(preset.bag, **user)
    # the loads' common start of compression, run once (each load continues from its checkpoint;
    # the paper's estimate makes it first and continues its own checkpoint from it too)
    part = shared_compression(preset, user, engine)
    part_stage = part and (run_folder(out, part), part.deck, ranks, run_variables(preset, part, user), say,
                           "compress.restart")
    if preset.estimate:
        out.mkdir(parents=True, exist_ok=True)
        estimate_paper(out, fill_vars, ranks, say, part_stage, resume and not estimate_only)
        if estimate_only:
            return
    elif not (resume and (out / MARKER).is_file()):
        fresh_dir(out)
    for name, line in preset.defaults_said.items():
        if name not in user:
            say("tbags shear %s: %s" % (preset.name, line))
    stage_once(out, "bag", ranks, fill_vars, say, "bag.data")
    stage_once(out, "fill", ranks, fill_vars, say, "fill.data")
    origin = (out / ".fill.vars").read_text()    # the fill's variables (a run resumes on the same fill)
    each_user = user
    if part:
        each_user = {k: v for k, v in user.items() if k != "compress_to"}    # the part's only
        each_user["compress_from"] = made_part(part_stage, run_folder(out, preset.runs[0]))

    def job(run, r):
        if engine == "liggghts":
            return lambda s: stage_liggghts(run_folder(out, run), r, run_variables(preset, run, user), s)
        return lambda s: stage_run(run_folder(out, run), run.deck, r, run_variables(preset, run, each_user), s,
                                   resume, origin)

    if preset.side_by_side and len(preset.runs) > 1:
        each = max(1, ranks // len(preset.runs))
        say("tbags shear: %s side by side, %d rank(s) each ..."
            % (", ".join(r.folder for r in preset.runs), each))
        side_by_side([job(r, each) for r in preset.runs], say)
    else:
        for r in preset.runs:
            job(r, ranks)(say)
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


def check(preset, out, say, in_realizations):
    if not preset.check:
        return
    args = [out] if preset.check == "trends" else ["--speed"] + [run_folder(out, r) for r in preset.runs]
    ok, _ = run_script("check_trends.py", args, say)
    if not ok:
        if preset.check == "speed":
            raise LaunchError("quasistatic: the S-u curves differ (above)")
        if not in_realizations:    # in realizations, the summary's check decides
            raise LaunchError("trends: a finding did not hold (above)")


def run_realizations(preset, n, seed, ranks, out, user, say, engine="lammps", resume=False):
    """n realizations of a preset (fills of seeds seed, seed + 1, ...) in out/r1 ... out/rn, as
    many at once as the cores allow, then their spread in out/realizations; resume: as
    run_preset's, in each."""
    t0 = time.time()
    out = Path(out)
    if not (resume and (out / MARKER).is_file()):
        fresh_dir(out)
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
    if preset.check == "trends":
        ok, text = run_script("check_trends.py", [out], say)
        (out / "realizations" / "check.txt").write_text(text)
        if not ok:
            raise LaunchError("trends: a finding did not hold in a realization (above; "
                              "%s/realizations/check.txt)" % out)


def stage_once(folder, deck, ranks, variables, say, product):
    """stage(), unless an earlier call made `product` in folder with the same variables (a stamp
    beside it), so that a long stage that finished is not run again."""
    stamp = Path(folder) / (".%s.vars" % deck)
    key = vars_key(variables)
    if (Path(folder) / product).is_file() and stamp.is_file() and stamp.read_text() == key:
        say("tbags shear: %s in %s: done before, reused" % (deck, folder))
        return
    stamp.unlink(missing_ok=True)
    stage(folder, deck, ranks, variables, say)
    stamp.write_text(key)


def vars_key(variables):
    return json.dumps({k: str(v) for k, v in variables.items()}, sort_keys=True)


def stage_run(folder, deck, ranks, variables, say, resume=False, origin=""):
    """One of a preset's runs (stage()), its variables stamped beside it. resume: a run that
    finished before with the same variables is kept, an interrupted one continues from its
    checkpoint (resume.py; the older checkpoint if the newer does not read), else it starts
    again; a run made with other variables (or another origin: its fill's) is not resumed."""
    folder = Path(folder)
    stamp = folder / (".%s.vars" % deck)
    key = vars_key(variables) + origin
    if resume and stamp.is_file():
        if stamp.read_text() != key:
            raise LaunchError("shear: --resume: %s was run with other -var values or another fill "
                              "(%s); run without --resume to start it again" % (folder, stamp))
        if resumed.finished(folder, deck):
            say("tbags shear: %s in %s: finished before, kept" % (deck, folder))
            return
        tries = resumed.checkpoints(folder, deck)
        for k, (name, extra) in enumerate(tries):
            say("tbags shear: %s in %s: resuming from %s" % (deck, folder, name))
            resumed.set_aside(folder, deck)
            try:
                stage(folder, deck, ranks, dict(variables, **extra), say)
            except LaunchError as e:
                if k + 1 == len(tries):
                    raise
                say("%s\n  (resuming from %s failed; the older checkpoint next)" % (e, name))
                continue
            resumed.merge_csv(folder / resumed.CSV[deck])
            return
    resumed.forget(folder, deck)
    folder.mkdir(parents=True, exist_ok=True)
    stamp.write_text(key)    # before the run: its checkpoints belong to these variables
    stage(folder, deck, ranks, variables, say)


def made_part(part_stage, where):
    """The loads' shared part of the compression made once (stage_once's arguments, part_stage);
    its checkpoint's path from the folder `where` (a run's, for -var compress_from)."""
    stage_once(*part_stage)
    return os.path.relpath(Path(part_stage[0]) / part_stage[-1], where)


def estimate_paper(out, fill_vars, ranks, say, part=None, reuse=False):
    """The paper run's cost measured on its own bag (fill_vars: its size and the user's -var
    values): the bag and its fill (the run's own, in out), the loads' shared part of the
    compression (part: stage_once's arguments, in out/compress; the run's loads reuse it), the
    rest of the compression and a short shear to a checkpoint (estimate/state), each made once; then a short
    stretch resumed from the checkpoint at 1, 2 and `ranks` ranks (estimate/np<P>) and a few steps
    at each of DECOMPOSITIONS ranks (estimate/decomp/np<P>: LAMMPS's own decomposition, for the
    scaling model); then the projection (inputs/project_time.py). reuse: an earlier projection
    is said again instead of timing anew."""
    counts = [1] + ([2] if ranks >= 2 else []) + ([ranks] if 2 < ranks <= os.cpu_count() else [])
    folder = Path(out) / "estimate"
    stage_once(out, "bag", ranks, fill_vars, say, "bag.data")
    stage_once(out, "fill", ranks, fill_vars, say, "fill.data")
    e = ESTIMATE
    shear = dict(fill_vars, v=e["v"], du_csv=e["du_csv"])
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
    restart = max((folder / "state").glob("shear.restart.*"), key=lambda f: f.stat().st_mtime).name
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
    if not run_script("project_time.py", [folder, "--ranks", ranks], say)[0]:
        raise LaunchError("paper: the projection failed (above)")
