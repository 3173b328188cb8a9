"""Every example deck (examples/STYLE/in.*, one or more per style) runs to the end, so the
examples a user starts from cannot rot, without a warning to reduce the time step; the film
example's S/F is its film friction. The
LIGGGHTS examples (examples/liggghts/) run in test_liggghts_bond.py."""
import re

import pytest

import lmprun

EXAMPLES = sorted(p for p in (lmprun.ROOT / "examples").glob("*/in.*") if p.parent.name != "liggghts")


def test_every_style_has_an_example():
    styles = {p.parent.name for p in EXAMPLES}
    assert {"pair_gran_hertz_rolling", "bond_bpm_yarn", "fix_wall_gran_servo", "fix_table_time"} <= styles


@pytest.mark.parametrize("deck", EXAMPLES, ids=[p.name for p in EXAMPLES])
def test_example_runs(tmp_path, deck):
    res = lmprun.run(deck, tmp_path, variables={"tbags": lmprun.ROOT}).check()
    assert "Total wall time" in res.output and "ERROR" not in res.output
    # shipped at a step they accept: the plates' chatter meter stays quiet (before its coherent
    # mean, grains landing read as chatter, and a film was judged by its near-zero net force)
    assert "reduce the timestep" not in res.output, res.output[-800:]
    if deck.name == "in.fix_table_time":     # the plate ends where the table ends, exactly
        m = re.search(r"TABLE/TIME EXAMPLE: plate u (\S+) mm", res.output)
        assert m and abs(float(m.group(1))) < 1e-9, res.output[-500:]
    if deck.name.endswith("_film"):
        m = re.search(r"FILM EXAMPLE: S/F (\S+) \(film friction (\S+)\), film moved (\S+) um", res.output)
        assert m, res.output[-500:]
        assert float(m.group(1)) == pytest.approx(float(m.group(2)), rel=0.005)
        assert abs(float(m.group(3))) < 20    # the film stays with the lower block (elastic give)
