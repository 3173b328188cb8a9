"""Committed states (launcher/tbagsrun/states.py): kept and restored bit for bit, a damaged one
refused, a stage made once skipped when its state is committed, and every committed state's
checksum (the paper bag's fill: its counts too)."""
import json
import lzma
import re
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "launcher"))
from tbagsrun import LaunchError, stages, states  # noqa: E402


def made(folder, body=b"LAMMPS data file\n\n5 atoms\n" * 100):
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "fill.data").write_bytes(body)
    (folder / ".fill.vars").write_text(stages.vars_key({"nx": 81, "ny": 81, "nz": 17}))
    return body


def test_keep_then_restore_bit_for_bit(tmp_path):
    body = made(tmp_path / "run")
    states.keep(tmp_path / "run", "fill", "fill.data", "paper-fill", "./tbags shear paper", root=tmp_path / "st")
    said = []
    key = stages.vars_key({"nx": 81, "ny": 81, "nz": 17})
    assert states.restore(tmp_path / "new", "fill", key, "fill.data", said.append, root=tmp_path / "st")
    assert (tmp_path / "new" / "fill.data").read_bytes() == body
    assert (tmp_path / "new" / ".fill.vars").read_text() == key
    assert "paper-fill" in said[0] and "checked" in said[0]
    # another stamp (another bag or -var value), deck or product: not this state
    other = stages.vars_key({"nx": 81, "ny": 81, "nz": 15})
    assert not states.restore(tmp_path / "n2", "fill", other, "fill.data", said.append, root=tmp_path / "st")
    assert not states.restore(tmp_path / "n3", "bag", key, "fill.data", said.append, root=tmp_path / "st")
    assert not (tmp_path / "n2" / "fill.data").exists()


def test_damaged_state_refused(tmp_path):
    made(tmp_path / "run")
    st = states.keep(tmp_path / "run", "fill", "fill.data", "x", "cmd", root=tmp_path / "st")
    with lzma.open(st / "fill.data.xz", "wb") as f:     # the content changed, the manifest not
        f.write(b"LAMMPS data file\n\n6 atoms\n" * 100)
    key = (tmp_path / "run" / ".fill.vars").read_text()
    with pytest.raises(LaunchError, match="damaged"):
        states.restore(tmp_path / "new", "fill", key, "fill.data", print, root=tmp_path / "st")
    assert not list((tmp_path / "new").iterdir())


def test_stage_once_uses_the_committed_state(tmp_path, monkeypatch):
    body = made(tmp_path / "run")
    states.keep(tmp_path / "run", "fill", "fill.data", "paper-fill", "cmd", root=tmp_path / "st")
    monkeypatch.setattr(states, "STATES", tmp_path / "st")

    def no_run(*a):
        raise AssertionError("the stage ran although its state is committed")
    monkeypatch.setattr(stages, "stage", no_run)
    said = []
    stages.stage_once(tmp_path / "out", "fill", 2, {"nx": 81, "ny": 81, "nz": 17}, said.append, "fill.data")
    assert (tmp_path / "out" / "fill.data").read_bytes() == body
    assert any("done before, reused" in s for s in said)
    # other variables: the stage runs
    with pytest.raises(AssertionError, match="the stage ran"):
        stages.stage_once(tmp_path / "o2", "fill", 2, {"nx": 81, "ny": 81, "nz": 17, "seed": 5}, said.append,
                          "fill.data")


def test_state_of_other_decks_not_restored(tmp_path, monkeypatch):
    """A deck the stage reads changed since the state was made: the stage runs instead."""
    made(tmp_path / "run")
    states.keep(tmp_path / "run", "fill", "fill.data", "x", "cmd", root=tmp_path / "st")
    key = (tmp_path / "run" / ".fill.vars").read_text()
    real = states.reads
    monkeypatch.setattr(states, "reads", lambda deck: dict(real(deck), **{"inputs/in.fill": "0" * 64}))
    said = []
    assert not states.restore(tmp_path / "new", "fill", key, "fill.data", said.append, root=tmp_path / "st")
    assert "changed: inputs/in.fill" in said[0] and not (tmp_path / "new" / "fill.data").exists()


def test_carry_takes_the_decks_new_contents_and_records_why(tmp_path, monkeypatch):
    """states.carry: a deck change shown not to change the run moves the state's stamp to the
    decks' new sha256, recording the old and new ones and why; refused without a reason, for a
    state whose decks did not change, and for a missing state."""
    made(tmp_path / "run")
    st = states.keep(tmp_path / "run", "fill", "fill.data", "x", "cmd", root=tmp_path / "st")
    old = json.loads((st / "manifest.json").read_text())["inputs"]["inputs/in.fill"]
    with pytest.raises(LaunchError, match="nothing to carry"):
        states.carry("x", "the same run bit for bit", root=tmp_path / "st")
    real = states.reads
    monkeypatch.setattr(states, "reads", lambda deck: dict(real(deck), **{"inputs/in.fill": "1" * 64}))
    with pytest.raises(LaunchError, match="say how"):
        states.carry("x", "same", root=tmp_path / "st")
    with pytest.raises(LaunchError, match="no state y"):
        states.carry("y", "the same run bit for bit", root=tmp_path / "st")
    assert states.carry("x", "the same run bit for bit", root=tmp_path / "st") == ["inputs/in.fill"]
    m = json.loads((st / "manifest.json").read_text())
    assert m["inputs"]["inputs/in.fill"] == "1" * 64 and states.changed_inputs(m) == []
    assert m["carried"] == [{"why": "the same run bit for bit", "files": {"inputs/in.fill": [old, "1" * 64]}}]
    key = (tmp_path / "run" / ".fill.vars").read_text()
    assert states.restore(tmp_path / "new", "fill", key, "fill.data", print, root=tmp_path / "st")


def header_counts(path):
    counts = {}
    with lzma.open(path, "rt") as f:
        for line in f:
            m = re.match(r"\s*(\d+)\s+(atoms|bonds)\s*$", line)
            if m:
                counts[m.group(2)] = int(m.group(1))
            if line.strip() in ("Atoms # sphere", "Atoms # hybrid", "Masses") or line.startswith("Atoms"):
                break
    return counts


COMMITTED = states.manifests()


@pytest.mark.parametrize("folder,m", COMMITTED, ids=[f.name for f, _ in COMMITTED])
def test_committed_state_checksum(tmp_path, folder, m):
    assert set(m) - {"carried"} == {"deck", "product", "vars", "size", "sha256", "made_by", "inputs"}
    for c in m.get("carried", []):
        assert len(c["why"].split()) >= 4 and c["files"]
    assert states.changed_inputs(m) == [], ("the decks changed since %s was made: remake it "
                                            "(states/README.md)" % folder.name)
    json.loads(m["vars"])
    states.unpack(folder, m, tmp_path / m["product"])    # raises if size or sha256 differ
    # the limits: a fill 20 MB, a checkpoint (the shared compression's) 50 MB
    assert (folder / (m["product"] + ".xz")).stat().st_size < (20e6 if m["product"] == "fill.data" else 50e6)


def test_paper_fill_committed():
    """The paper preset's fill is committed: 17,922 bag particles + 97,130 grains, 35,840 bonds,
    and its stamp is the one the preset's fill stage computes (so the preset skips the fill)."""
    folder = states.STATES / "paper-fill"
    m = json.loads((folder / "manifest.json").read_text())
    assert header_counts(folder / "fill.data.xz") == {"atoms": 17922 + 97130, "bonds": 35840}
    from tbagsrun.cli import parse
    o = parse(["paper"])    # what `./tbags shear paper` gives its fill stage (shear.run_preset)
    assert m["vars"] == stages.vars_key(dict(o.preset.bag, **dict(o.variables, seed=o.seed)))


def test_paper_compression_committed():
    """The paper preset's shared compression is committed (0.9 of 1960 N, from the committed fill),
    and its stamp is the one the preset's part stage computes (so the preset skips it)."""
    m = json.loads((states.STATES / "paper-compress" / "manifest.json").read_text())
    from tbagsrun import shear
    from tbagsrun.cli import parse
    o = parse(["paper"])
    part = shear.shared_compression(o.preset, o.variables, "lammps")
    assert m["deck"] == part.deck and m["product"] == "compress.restart"
    assert m["vars"] == stages.vars_key(shear.part_variables(o.preset, part, dict(o.variables, seed=o.seed)))
    # another speed (-var v) reuses it
    assert m["vars"] == stages.vars_key(shear.part_variables(o.preset, part, dict(o.variables, seed=o.seed, v=0.016)))


def test_reads_lists_every_file_the_decks_read():
    """states.READS is kept by hand: every file a listed deck reads unconditionally through
    ${tbags}/... (its includes, followed, and their tables) is in its entry, so that an edit of
    any of them stops a committed state from being restored. Conditional reads (`if ... then
    "include ..."`: the stack's stack.lmp, the calibrated sand) are left out on purpose: the
    committed states are made without them."""
    root = Path(states.ROOT)
    ref = re.compile(r"\$\{tbags\}/(\S+?)[\"'\s]")

    def reads(name, seen):
        seen.add(name)
        for line in (root / name).read_text().splitlines():
            code = line.split("#", 1)[0]
            if code.lstrip().startswith("if "):
                continue
            for path in ref.findall(code + " "):
                if path not in seen and (root / path).is_file():
                    if path.endswith(".lmp"):
                        reads(path, seen)
                    else:
                        seen.add(path)
        return seen

    for deck, listed in states.READS.items():
        found = reads("inputs/in.%s" % deck, set())
        assert found <= set(listed), (deck, sorted(found - set(listed)))
    assert reads("inputs/in.shear", set()) == set(states.READS["shear"])
