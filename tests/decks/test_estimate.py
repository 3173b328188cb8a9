"""./tbags shear paper --estimate's workflow on the tiny bag (the same stages as on the paper's):
bag and fill made once and reused, the checkpoint, timed stretches at 1 and 2 ranks resumed from
it, a decomposition run at 4 ranks; the projection and the scaling model, whose per-rank counts
agree with LAMMPS's own (grid, Nlocal, Nghost, Neighs) on the real decomposition."""
import lmprun
from tbagsrun import shear


def test_estimate_on_the_tiny_bag(tmp_path, monkeypatch):
    # a short checkpoint and stretch (the tiny bag is 9 x 9 x 5: 411 atoms)
    monkeypatch.setattr(shear, "ESTIMATE", dict(v=0.004, du_csv=2e-6, du_dump=4e-6, u_state=4e-6, u_timed=2e-6))
    monkeypatch.setattr(shear, "DECOMPOSITIONS", (4,))
    said = []
    shear.estimate_paper(tmp_path, lmprun.TINY_BAG, 2, said.append)
    text = (tmp_path / "estimate" / "projection.txt").read_text()
    assert "measured on the 9 x 9 x 5 bag" in text and "Scaling model" in text
    assert "counts at 4 ranks against LAMMPS's (grid, Nlocal, Nghost, Neighs; mean and max): agree" in text
    for p in (1, 2):
        assert "for 333 steps" in (tmp_path / "estimate" / ("np%d" % p) / "log.shear").read_text()
    # a second call reuses the bag, fill and checkpoint
    said.clear()
    shear.estimate_paper(tmp_path, lmprun.TINY_BAG, 2, said.append)
    assert sum("done before, reused" in line for line in said) == 3
