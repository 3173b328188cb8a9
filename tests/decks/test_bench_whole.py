"""./tbags bench --whole's decks stay runnable (a benchmark is not a timed test: nothing here is
timed): in.shear writes the sheared state (-var state 1), the stock deck runs on it for 2,000
steps with no particle or bond lost, and the benchmark reads both runs' section times."""
import sys

import lmprun

sys.path.insert(0, str(lmprun.ROOT / "bench"))
import whole  # noqa: E402


def test_stock_deck_runs_on_the_sheared_state(tmp_path):
    lmprun.bag_and_fill(tmp_path)
    ours = lmprun.run(lmprun.INPUTS / "in.shear", tmp_path, variables=dict(
        lmprun.TINY_BAG, v=0.02, ufinal=0.0002, state=1)).check()
    assert (tmp_path / "state.data").is_file()
    t = whole.timing(ours.output)
    assert t["steps"] > 0 and t["atoms"] == 411 and t["Pair"] > 0 and t["Bond"] > 0
    stock = lmprun.run(lmprun.ROOT / "bench" / "in.bench_whole_stock", tmp_path / "stock", variables=dict(
        state=tmp_path / "state.data", ztop=whole.top_plate(tmp_path), v=0.015, dt=1.5e-6, nsteps=2000)).check()
    s = whole.timing(stock.output)
    assert s["steps"] == 2000 and s["atoms"] == 411 and s["Bond"] > 0
    assert whole.bond_count(tmp_path) == 512
