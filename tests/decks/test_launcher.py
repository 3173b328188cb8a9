"""./tbags shear end to end on a tiny bag, where the launcher itself decides: it never clears a
folder of the user's, and it works from a repository and into a folder whose paths have spaces
(the decks include the repository's files through ${tbags}, which LAMMPS splits at spaces)."""
import os
import shutil
import subprocess

import lmprun
import pytest

TINY = ["-np", "1", "-var", "nx", "9", "-var", "ny", "9", "-var", "nz", "5", "-var", "v", "0.02",
        "-var", "ufinal", "0.0003"]


# S at u = 0.79 mm of the tiny bag in this protocol over fills of seeds 4821-4824 (measured with
# ./tbags shear and the test's -var values: 65.4, 59.0, 60.7, 62.8 N)
TINY_SD_S = 2.78    # N (mean 62.0 N)


def launcher_env(**extra):
    return dict(os.environ, TBAGS_BUILD_DIR=os.environ.get("TBAGS_BUILD", str(lmprun.ROOT / "build")), **extra)


def test_out_never_clears_a_users_folder(tmp_path):
    mine = tmp_path / "mine"
    mine.mkdir()
    (mine / "thesis.tex").write_text("keep me")
    r = subprocess.run([str(lmprun.ROOT / "tbags"), "shear", "--out", str(mine)] + TINY,
                       env=launcher_env(), capture_output=True, text=True, timeout=600 * lmprun.SLOWDOWN)
    assert r.returncode != 0 and "is not empty and was not made by ./tbags shear" in r.stderr
    assert (mine / "thesis.tex").read_text() == "keep me"


def test_paths_with_spaces(tmp_path):
    """A copy of the launcher, decks and post-processing under 'my repo', writing to 'out dir':
    the demo protocol runs through to its figures (before the launcher passed the repository's
    path to LAMMPS as it is, and in.fill's include failed)."""
    repo = tmp_path / "my repo"
    repo.mkdir()
    shutil.copy2(lmprun.ROOT / "tbags", repo / "tbags")
    for folder in ("launcher", "inputs", "postprocess", "cmake"):
        shutil.copytree(lmprun.ROOT / folder, repo / folder, ignore=shutil.ignore_patterns("results", "images"))
    out = tmp_path / "out dir"
    r = subprocess.run([str(repo / "tbags"), "shear", "--out", str(out)] + TINY,
                       env=launcher_env(TBAGS_CACHE=str(tmp_path / "cache")),
                       capture_output=True, text=True, timeout=900 * lmprun.SLOWDOWN)
    print(r.stdout[-3000:], r.stderr[-2000:])
    assert r.returncode == 0
    assert "SHEARED: u 0.300 mm" in r.stdout
    assert (out / "shear.csv").is_file() and (out / "figures" / "shear.png").is_file()
    link = next((tmp_path / "cache").glob("repo-*"))
    assert link.resolve() == repo.resolve() and " " not in str(link)


def checksums(folder):
    import hashlib
    return {str(f.relative_to(folder)): hashlib.sha256(f.read_bytes()).hexdigest()
            for f in sorted(folder.rglob("*")) if f.is_file()}


def test_loads_share_one_compression(tmp_path):
    """A preset of three loads on one fill (as trends, paper and cyclic): the launcher compresses
    once to 0.9 of the smallest load (compress/), then each load continues from that checkpoint to
    its own F_v, side by side, and the figures are made from the three runs."""
    import re
    from tbagsrun import shear
    from tbagsrun.presets import LOADS, Preset, per_load
    from tbagspost.run import loops    # (postprocess/ is on the path through tbagsrun.resume)
    preset = Preset("loads", "loads", lmprun.TINY_BAG, per_load("shear", v=0.02, ufinal=0.0003), True, "figures")
    said = []
    shear.run_preset(preset, 2, tmp_path / "out", {}, said.append)
    text = "\n".join(said)
    print(text)
    out = tmp_path / "out"
    assert (out / "compress" / "compress.restart").is_file()
    part = [line for line in said if "COMPRESSION PART" in line]
    assert len(part) == 1 and "(0.9 of %s" % ("%.14g" % (1960 * 7 * 7 / 79 ** 2))[:8] in part[0]
    n_part = int(re.search(r"after (\d+) steps", part[0]).group(1))
    for f in LOADS:
        log = (out / ("F%d" % f) / "log.shear").read_text()
        assert "read_restart    ../compress/compress.restart" in log
        fv, target = map(float, re.search(r"^COMPRESSED: F_v (\S+) N \(target (\S+)\)", log, re.M).groups())
        assert abs(target - f * 7 * 7 / 79 ** 2) < 1e-9 and abs(fv - target) < 0.005 * target
        # the rest of the compression only
        rest = loops(log)[0]["steps"]
        assert 0 < rest < n_part
        assert "SHEARED: u 0.300 mm" in log
    assert (out / "F1960" / "figures" / "shear.png").is_file()


def test_resume_an_interrupted_run(tmp_path):
    """./tbags shear killed while shearing, after its first checkpoint, then called again with
    --resume: the fill is reused, the shear continues from its newer checkpoint, and the CSV ends
    with one row for every du_csv of u to u_final (the rows the killed run wrote past its
    checkpoint replaced by the resumed run's), from which the figures are made."""
    import signal
    import time
    import numpy as np
    out = tmp_path / "out"
    argv = [str(lmprun.ROOT / "tbags"), "shear", "--out", str(out)] + TINY[:-3] + [
        "-var", "ufinal", "0.0008", "-var", "du_dump", "0.0002", "-var", "du_csv", "0.00002"]
    p = subprocess.Popen(argv, env=launcher_env(), stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                         text=True, start_new_session=True)
    t0 = time.time()
    try:    # killed once a checkpoint exists and rows past it are written (u > 0.24 mm)
        while time.time() - t0 < 600 and p.poll() is None:
            rows = (out / "shear.csv").read_text().splitlines() if (out / "shear.csv").is_file() else []
            if (out / "shear.restart.1").is_file() and len(rows) > 2 + 13:
                break
            time.sleep(0.05)
    finally:
        os.killpg(p.pid, signal.SIGKILL)
        p.wait()
    assert (out / "shear.restart.1").is_file() and "SHEARED" not in (out / "screen.shear.txt").read_text()
    interrupted = (out / "shear.csv").read_text().count("\n") - 2    # rows (a header, a title)
    # called again without --resume, or with --resume and another -var value: refused before
    # anything runs, every file as it was (be13c81 removed the folder, or re-made the fill)
    before = checksums(out)
    for extra in ([], ["--resume", "-var", "e0", "0.70"], ["--resume", "-var", "v", "0.03"]):
        r = subprocess.run(argv + extra, env=launcher_env(), capture_output=True, text=True, timeout=300 * lmprun.SLOWDOWN)
        assert r.returncode != 0 and "Nothing was changed" in r.stderr, r.stdout + r.stderr
        assert ("--resume to continue" in r.stderr) == (not extra)
        assert checksums(out) == before
    r = subprocess.run(argv + ["--resume"], env=launcher_env(), capture_output=True, text=True, timeout=900 * lmprun.SLOWDOWN)
    print(r.stdout[-3000:], r.stderr[-2000:])
    assert r.returncode == 0
    assert "fill in %s: done before, reused" % out in r.stdout
    assert "resuming from shear.restart." in r.stdout and "SHEARED: u 0.800 mm" in r.stdout
    rows = np.genfromtxt(out / "shear.csv", delimiter=",", names=True)
    print("killed after %d rows; resumed to %d" % (interrupted, len(rows)))
    assert 14 <= interrupted < len(rows) == 41
    # (the u = 0 row is one step: the first interval's mean is 0.01 mm past it)
    steps = np.diff(rows["u_mm"])
    assert steps[0] == pytest.approx(0.01, abs=1e-3) and np.all(np.abs(steps[1:] - 0.02) < 1e-3)
    assert rows["u_mm"][-1] == pytest.approx(0.79, abs=2e-3)
    assert (out / "screen.shear.txt.1").is_file() and (out / "figures" / "shear.png").is_file()
    # called again: the finished run is kept, not run
    r = subprocess.run(argv + ["--resume"], env=launcher_env(), capture_output=True, text=True, timeout=900 * lmprun.SLOWDOWN)
    assert r.returncode == 0 and "shear in %s: finished before, kept" % out in r.stdout
    # what a resume gives (README): the rows up to the checkpoint are the straight run's, bit for
    # bit; after it the run parts as another sample of the fill would, within the spread of S
    # between fills (TINY_SD_S)
    straight = tmp_path / "straight"
    r = subprocess.run([w if w != str(out) else str(straight) for w in argv], env=launcher_env(),
                       capture_output=True, text=True, timeout=900 * lmprun.SLOWDOWN)
    assert r.returncode == 0
    resumed_rows = [line for line in (out / "shear.csv").read_text().splitlines() if line[:1].isdigit()]
    straight_rows = [line for line in (straight / "shear.csv").read_text().splitlines() if line[:1].isdigit()]
    assert len(resumed_rows) == len(straight_rows) == 41
    same = next(k for k, (a, b) in enumerate(zip(resumed_rows, straight_rows)) if a != b)
    ref = np.genfromtxt(straight / "shear.csv", delimiter=",", names=True)
    print("resumed: rows identical to the straight run's up to u = %.2f mm; S at the end %.2f N "
          "against %.2f N (fills' sd %.1f N)" % (ref["u_mm"][same - 1], rows["S_N"][-1], ref["S_N"][-1], TINY_SD_S))
    assert ref["u_mm"][same - 1] >= 0.19    # the first checkpoint is at 0.2 mm
    assert abs(rows["S_N"][-1] - ref["S_N"][-1]) < 2 * TINY_SD_S


def test_stopped_compression_continues_from_its_checkpoint(tmp_path):
    """The loads' shared compression (hours on the paper's bag) writes checkpoints while it runs
    (compress.part.1/2 every compress_every steps); a stage stopped before compress.restart
    continues from the newer one when called again with the same variables (stages.stage_once),
    and ends where the straight run ends: the same step, F_v and w."""
    import re
    from tbagsrun import stages
    lmprun.filled_bag(tmp_path / "fill")
    part = dict(lmprun.TINY_BAG, Fpaper=1960, v=0.02, compress_to=0.9, compress_every=1000, fill="../fill/fill.data")
    straight = lmprun.run(lmprun.INPUTS / "in.shear", tmp_path / "straight", variables=part).check().output
    line = re.search(r"^COMPRESSION PART: F_v (\S+) N .* after (\d+) steps, w (\S+) mm", straight, re.M)
    n_steps = int(line.group(2))
    # a stop after the last checkpoint (the newer of the two, unless written at the step the part
    # ended): the folder as the stopped stage left it (its stamp, the checkpoint, no product)
    parts = sorted((tmp_path / "straight").glob("compress.part.[12]"), key=lambda f: f.stat().st_mtime)
    use, last = (parts[-1], n_steps // 1000 * 1000) if n_steps % 1000 else (parts[-2], n_steps - 1000)
    assert last > 0, "the tiny bag's compression took fewer steps than one checkpoint"
    stopped = tmp_path / "stopped"
    stopped.mkdir()
    (stopped / use.name).write_bytes(use.read_bytes())
    (stopped / ".shear.vars").write_text(stages.vars_key(part))
    said = []
    stages.stage_once(stopped, "shear", 1, part, said.append, "compress.restart")
    print("\n".join(said))
    assert "tbags shear: shear in %s: continuing from its checkpoint %s" % (stopped, use.name) in said
    again = next(s for s in said if "COMPRESSION PART" in s)
    m = re.search(r"F_v (\S+) N .* after (\d+) steps, w (\S+) mm", again)
    print("straight: %s steps, F_v %s N, w %s mm; continued from step %d: %s steps, F_v %s N, w %s mm"
          % (n_steps, line.group(1), line.group(3), last, m.group(2), m.group(1), m.group(3)))
    # (the restart's fresh force evaluation differs from the straight run's by round-off)
    assert int(m.group(2)) == n_steps
    assert float(m.group(1)) == pytest.approx(float(line.group(1)), rel=5e-3)
    assert float(m.group(3)) == pytest.approx(float(line.group(3)), abs=1e-3)
    assert (stopped / "compress.restart").is_file() and not list(stopped.glob("compress.part.*"))
    assert "read_restart    compress.part" in (stopped / "log.shear").read_text()
    # called again: reused, not run
    said.clear()
    stages.stage_once(stopped, "shear", 1, part, said.append, "compress.restart")
    assert said == ["tbags shear: shear in %s: done before, reused" % stopped]
