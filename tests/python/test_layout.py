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
