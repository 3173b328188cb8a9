"""./tbags shear paper --estimate's workflow on the tiny bag (the same stages as on the paper's):
bag and fill made once and reused, the checkpoint, timed stretches at 1 and 2 ranks resumed from
it, a decomposition run at 4 ranks; the projection and the scaling model, whose per-rank counts
agree with LAMMPS's own (grid, Nlocal, Nghost, Neighs) on the real decomposition."""
import lmprun
from tbagsrun import estimate, shear, stages


def test_estimate_on_the_tiny_bag(tmp_path, monkeypatch):
    # a short checkpoint and stretch (the tiny bag is 9 x 9 x 5: 411 atoms)
    monkeypatch.setattr(estimate, "ESTIMATE", dict(v=0.004, du_csv=2e-6, du_dump=4e-6, u_state=4e-6, u_timed=2e-6))
    monkeypatch.setattr(estimate, "DECOMPOSITIONS", (4,))
    said = []
    estimate.estimate_paper(tmp_path, lmprun.TINY_BAG, 2, said.append)
    text = (tmp_path / "estimate" / "projection.txt").read_text()
    assert "measured on the 9 x 9 x 5 bag" in text and "Scaling model" in text
    assert "counts at 4 ranks against LAMMPS's (grid, Nlocal, Nghost, Neighs; mean and max): agree" in text
    for p in (1, 2):
        assert "for 333 steps" in (tmp_path / "estimate" / ("np%d" % p) / "log.shear").read_text()
    # a second call reuses the bag, fill and checkpoint
    said.clear()
    estimate.estimate_paper(tmp_path, lmprun.TINY_BAG, 2, said.append)
    assert sum("done before, reused" in line for line in said) == 3


def test_estimate_makes_the_shared_part_that_the_run_reuses(tmp_path, monkeypatch):
    """`./tbags shear paper --estimate` compresses through the loads' shared part (compress/, the
    smallest load to 0.9 of its F_v) and continues its checkpoint from it; the projection counts
    the part's own steps once; the full run would reuse the part (stage_once's stamp)."""
    import re
    from tbagsrun.presets import PRESETS
    monkeypatch.setattr(estimate, "ESTIMATE", dict(v=0.004, du_csv=2e-6, du_dump=4e-6, u_state=4e-6, u_timed=2e-6))
    monkeypatch.setattr(estimate, "DECOMPOSITIONS", ())
    said = []
    shear.run_preset(PRESETS["paper"], 2, tmp_path, dict(lmprun.TINY_BAG), said.append, estimate_only=True)
    part = next(line for line in said if "COMPRESSION PART" in line)
    n_part = int(re.search(r"after (\d+) steps", part).group(1))
    state = (tmp_path / "estimate" / "state" / "log.shear").read_text()
    assert "read_restart    ../../compress/compress.restart" in state and "(0.9 of 15.3885" in part
    # the short shear runs at the load of the preset's first run (--loads F1960: 1.96 kN's)
    import json
    assert json.loads((tmp_path / "estimate" / "state" / ".shear.vars").read_text())["Fpaper"] == "5500"
    text = (tmp_path / "estimate" / "projection.txt").read_text()
    print(part, text.splitlines()[1], sep="\n")
    assert "of which %d shared by the loads" % round(n_part * 15 / 3) in text
    part_stage = (tmp_path / "compress", "shear", 2, shear.part_variables(
        PRESETS["paper"], shear.shared_compression(PRESETS["paper"], {}, "lammps"), dict(lmprun.TINY_BAG)),
        said.append, "compress.restart")
    said.clear()
    stages.stage_once(*part_stage)
    assert said == ["tbags shear: shear in %s: done before, reused" % (tmp_path / "compress")]
