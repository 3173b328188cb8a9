"""./tbags shear end to end on a tiny bag, where the launcher itself decides: it never clears a
folder of the user's, and it works from a repository and into a folder whose paths have spaces
(the decks include the repository's files through ${tbags}, which LAMMPS splits at spaces)."""
import os
import shutil
import subprocess

import lmprun

TINY = ["-np", "1", "-var", "nx", "9", "-var", "ny", "9", "-var", "nz", "5", "-var", "v", "0.02",
        "-var", "ufinal", "0.0003"]


def launcher_env(**extra):
    return dict(os.environ, TBAGS_BUILD_DIR=os.environ.get("TBAGS_BUILD", str(lmprun.ROOT / "build")), **extra)


def test_out_never_clears_a_users_folder(tmp_path):
    mine = tmp_path / "mine"
    mine.mkdir()
    (mine / "thesis.tex").write_text("keep me")
    r = subprocess.run([str(lmprun.ROOT / "tbags"), "shear", "--out", str(mine)] + TINY,
                       env=launcher_env(), capture_output=True, text=True, timeout=600)
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
                       capture_output=True, text=True, timeout=900)
    print(r.stdout[-3000:], r.stderr[-2000:])
    assert r.returncode == 0
    assert "SHEARED: u 0.300 mm" in r.stdout
    assert (out / "shear.csv").is_file() and (out / "figures" / "shear.png").is_file()
    link = next((tmp_path / "cache").glob("repo-*"))
    assert link.resolve() == repo.resolve() and " " not in str(link)


def test_loads_share_one_compression(tmp_path):
    """A preset of three loads on one fill (as trends, paper and cyclic): the launcher compresses
    once to 0.9 of the smallest load (compress/), then each load continues from that checkpoint to
    its own F_v, side by side, and the figures are made from the three runs."""
    import re
    from tbagsrun import shear
    from tbagsrun.presets import LOADS, Preset, per_load
    from tbagspost.run import loops    # (postprocess/ is on the path through tbagsrun.shear)
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
