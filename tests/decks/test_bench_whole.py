"""./tbags bench --whole's decks stay runnable (a benchmark is not a timed test: nothing here is
timed): in.shear writes the sheared state (-var state 1); the benchmark reads it back as a
checkpoint, resumes our run from it for a given number of steps (in.shear -var steps) and runs the
stock deck on it with no particle or bond lost, and reads both runs' section times."""
import sys

import lmprun

sys.path.insert(0, str(lmprun.ROOT / "bench"))
import whole  # noqa: E402


def test_both_setups_run_from_the_sheared_state(tmp_path):
    lmprun.bag_and_fill(tmp_path)
    made = lmprun.run(lmprun.INPUTS / "in.shear", tmp_path, variables=dict(
        lmprun.TINY_BAG, v=0.02, ufinal=0.0002, du_dump=0.0002, state=1)).check()
    t = whole.timing(made.output)
    assert t["steps"] > 0 and t["atoms"] == 411 and t["Pair"] > 0 and t["Bond"] > 0
    state = whole.State(tmp_path)
    assert state.bag == lmprun.TINY_BAG and state.restart.name.startswith("shear.restart.")
    assert state.dt == 1.5e-6 and abs(state.ztop) > 0
    # an earlier run's contact dump in the folder, at a later step: not counted
    (tmp_path / "ours").mkdir()
    (tmp_path / "ours" / "dump.contacts.99999999").write_text(
        "ITEM: TIMESTEP\n99999999\nITEM: NUMBER OF ENTRIES\n1\nITEM: ENTRIES index\n1\n")
    ours = whole.run_ours(state, tmp_path / "ours", 1, 300)
    assert ours["steps"] == 300 and ours["atoms"] == 411 and ours["Bond"] > 0
    # the contacts per contact-step are counted from this run's contact dump: its entries
    dumps = [f for f in (tmp_path / "ours").glob("dump.contacts.*") if not f.name.endswith(".99999999")]
    assert len(dumps) == 1
    lines = dumps[0].read_text().splitlines()
    entries = lines[lines.index(next(x for x in lines if x.startswith("ITEM: ENTRIES"))) + 1:]
    assert whole.contact_count(tmp_path / "ours") == len(entries) > 0
    assert whole.contact_count(tmp_path / "none") is None
    stock = whole.run_stock(state, tmp_path / "stock", 1, 2000)
    assert stock["steps"] == 2000 and stock["atoms"] == 411 and stock["Bond"] > 0
    assert whole.bond_count(state.data) == 512
