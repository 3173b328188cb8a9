"""The repository's layout: decks in inputs/ (Python there only to generate an input file),
every check and tool a module of tbagspost, which never reaches into the launcher or edits
sys.path; results in results/."""
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
GENERATORS = {"inputs/histories/make_irregular.py"}    # writes the committed history next to it


def test_inputs_hold_decks_not_tools():
    py = {str(p.relative_to(ROOT)) for p in (ROOT / "inputs").rglob("*.py")}
    assert py <= GENERATORS, "Python in inputs/: %s (make it a tbagspost module)" % sorted(py - GENERATORS)
    assert not (ROOT / "inputs" / "results").exists() and (ROOT / "results" / "README.md").is_file()


def test_tbagspost_is_a_package_without_path_edits():
    for p in sorted((ROOT / "postprocess" / "tbagspost").glob("*.py")):
        text = p.read_text()
        assert "sys.path" not in text, "%s edits sys.path" % p.name
        assert not re.search(r"^\s*(from|import)\s+tbagsrun", text, re.M), "%s imports the launcher" % p.name


def test_results_carry_no_machine_paths():
    """Committed results, states, calibration results and benchmark records name no folder of the
    machine that made them (a worktree in /tmp, a home): <repo>, <out> and the like stand for them."""
    machine = re.compile(r"(?<![\w<])/(tmp|root|home|work)/")
    found = []
    for top in ("results", "states", "calibration/results", "bench"):
        for p in sorted((ROOT / top).rglob("*")):
            if p.is_file() and p.suffix not in (".png", ".xz", ".py") and p.stat().st_size < 5e7:
                text = p.read_text(errors="replace")
                found += ["%s:%d" % (p.relative_to(ROOT), text[:m.start()].count("\n") + 1)
                          for m in machine.finditer(text)][:1]
    assert not found, "machine paths in committed files: %s" % found[:20]
