"""calibration/fit.py refuses to replace a report (and the sand_calibrated.lmp the decks read)
with one of another search unless --replace; the same search (any budget) extends it."""
import json
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "calibration"))
import fit  # noqa: E402
from tbagscal.common import FitError  # noqa: E402
from tbagscal.report import check_replace, options  # noqa: E402


def test_another_search_needs_replace(tmp_path):
    out = tmp_path / "results"
    out.mkdir()
    args = ["--fit", "mu,mur,E", "--seeds", "2", "--mu", "0.379", "--out", str(out)]
    a = fit.parse_args(args + ["--budget", "24"])
    check_replace(a)                                     # no report yet
    (out / "report.md").write_text("# report\n")
    (out / "sand_calibrated.lmp").write_text("variable sand_mu equal 0.4\n")
    (out / "options.json").write_text(json.dumps(dict(options(a), seeds=[7331, 7332])))
    check_replace(fit.parse_args(args + ["--budget", "30", "--jobs", "1"]))    # extends it
    with pytest.raises(FitError, match=r"differs in: n_seeds, search\).*sand_calibrated.lmp.*--replace"):
        check_replace(fit.parse_args(["--out", str(out)]))    # the default search from the paper's set
    with pytest.raises(FitError, match="differs in: cell"):
        check_replace(fit.parse_args(args + ["--cell", "periodic"]))
    check_replace(fit.parse_args(["--out", str(out), "--replace"]))
    (out / "options.json").unlink()                      # a report of an older fit.py
    with pytest.raises(FitError, match="options.json"):
        check_replace(a)
