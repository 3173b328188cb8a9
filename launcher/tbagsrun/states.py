"""Committed states: a long stage's product (the paper bag's fill, ...) kept in the repository
under states/<name>/ (the product xz-compressed, and manifest.json: the deck, the product, the
stage's -var stamp, the sha256 and size of the product, the command that made it), so that a
preset on a new machine skips hours of work. stages.stage_once restores a state whose deck,
product and stamp are the stage's own, checksum verified, before it would run the stage.

Keep a state (from the launcher/ folder, after the stage finished):
  /usr/bin/python3 -m tbagsrun.states keep FOLDER DECK PRODUCT NAME "COMMAND THAT MADE IT"
Carry a state over a change of its decks that leaves its run unchanged bit for bit (say how that
was shown; the manifest records it with the files' old and new sha256):
  /usr/bin/python3 -m tbagsrun.states carry NAME "HOW THE RUN WAS SHOWN UNCHANGED"
"""
import hashlib
import json
import lzma
import shutil
import sys
from pathlib import Path

from . import ROOT, LaunchError

STATES = ROOT / "states"
CHUNK = 1 << 20
# the files a stage reads (its deck and what it includes); a state made from other contents of
# them is not restored: the stage runs instead. Other decks: their own and every include. Kept by
# hand; tests/python/test_states.py checks it against the decks' unconditional includes.
READS = {"bag": ("inputs/in.bag",),
         "fill": ("inputs/in.bag", "inputs/in.fill", "inputs/sand.lmp", "inputs/fabric.lmp",
                  "inputs/yarn.lmp", "inputs/yarn_pp_tape.table"),
         # one bag between the plates (stack.lmp only with -var bags > 1)
         "shear": ("inputs/in.shear", "inputs/between_plates.lmp", "inputs/sand.lmp", "inputs/fabric.lmp",
                   "inputs/yarn.lmp", "inputs/yarn_pp_tape.table")}


def reads(deck, root=ROOT):
    """{path: sha256} of the files `deck` reads."""
    names = READS.get(deck) or sorted({"inputs/in.%s" % deck} | {str(p.relative_to(root)) for p in
                                      (Path(root) / "inputs").glob("*.lmp")} | {"inputs/yarn_pp_tape.table"})
    return {n: sha256(Path(root) / n) for n in names}


def changed_inputs(m):
    """The files the state's deck reads whose contents differ from those that made it."""
    now = reads(m["deck"])
    return sorted(n for n in set(now) | set(m["inputs"]) if now.get(n) != m["inputs"].get(n))


def sha256(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(CHUNK), b""):
            h.update(block)
    return h.hexdigest()


def manifests(root=None):
    """[(folder, manifest dict)] of the committed states (root: states/)."""
    return [(m.parent, json.loads(m.read_text())) for m in sorted(Path(root or STATES).glob("*/manifest.json"))]


def find(deck, product, key, root=None):
    """(folder, manifest) of the committed state made by `deck` with the stamp `key`, or None."""
    for folder, m in manifests(root):
        if m["deck"] == deck and m["product"] == product and m["vars"] == key:
            return folder, m
    return None


def unpack(state, m, target):
    """The product of the state (its folder and manifest) decompressed to target, its size and
    sha256 checked (LaunchError if not: the committed file is damaged; nothing is left at target)."""
    part = Path(str(target) + ".part")
    with lzma.open(Path(state) / (m["product"] + ".xz")) as src, open(part, "wb") as dst:
        shutil.copyfileobj(src, dst, CHUNK)
    if part.stat().st_size != m["size"] or sha256(part) != m["sha256"]:
        part.unlink()
        raise LaunchError("states: %s does not match its manifest (size or sha256): the committed "
                          "file is damaged; `git checkout -- %s`, or remove the folder to make the "
                          "stage again (%s)" % (state, state, m["made_by"]))
    part.replace(target)


def restore(folder, deck, key, product, say, root=None):
    """folder/product from a committed state made with the same deck and stamp, and the stamp
    beside it (stages.stage_once then reuses it); False when there is none."""
    found = find(deck, product, key, root)
    if found is None:
        return False
    state, m = found
    changed = changed_inputs(m)
    if changed:
        say("tbags shear: the committed state %s was made by other decks (changed: %s): the %s stage "
            "runs (states/README.md: keep it again)" % (Path(state).name, ", ".join(changed), deck))
        return False
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    unpack(state, m, folder / product)
    (folder / (".%s.vars" % deck)).write_text(key)
    say("tbags shear: %s in %s: the committed state %s (made by %s; sha256 %s... checked)"
        % (deck, folder, Path(state).name, m["made_by"], m["sha256"][:12]))
    return True


def keep(folder, deck, product, name, made_by, root=None):
    """Commit folder/product (made by `deck`, its stamp beside it) as the state `name`."""
    folder = Path(folder)
    stamp = folder / (".%s.vars" % deck)
    if not (folder / product).is_file() or not stamp.is_file():
        raise LaunchError("states: %s needs %s and its stamp %s (a finished stage)"
                          % (folder, product, stamp.name))
    state = Path(root or STATES) / name
    state.mkdir(parents=True, exist_ok=True)
    with open(folder / product, "rb") as src, lzma.open(state / (product + ".xz"), "wb", preset=9) as dst:
        shutil.copyfileobj(src, dst, CHUNK)
    m = dict(deck=deck, product=product, vars=stamp.read_text(), size=(folder / product).stat().st_size,
             sha256=sha256(folder / product), made_by=made_by, inputs=reads(deck))
    (state / "manifest.json").write_text(json.dumps(m, indent=1) + "\n")
    return state


def carry(name, why, root=None):
    """The state `name` takes its decks' present contents, for a change shown (`why`) to leave its
    run bit for bit as it was; the manifest's `carried` list records each such change."""
    state = Path(root or STATES) / name
    if not (state / "manifest.json").is_file():
        raise LaunchError("states: no state %s (states/<name>/manifest.json)" % name)
    if len(why.split()) < 4:
        raise LaunchError("states: carry %s: say how the run was shown unchanged (a sentence)" % name)
    m = json.loads((state / "manifest.json").read_text())
    changed = changed_inputs(m)
    if not changed:
        raise LaunchError("states: %s: its decks have not changed; nothing to carry" % name)
    now = reads(m["deck"])
    m.setdefault("carried", []).append(dict(why=why, files={n: [m["inputs"].get(n), now.get(n)] for n in changed}))
    m["inputs"] = now
    (state / "manifest.json").write_text(json.dumps(m, indent=1) + "\n")
    return changed


if __name__ == "__main__":
    if len(sys.argv) == 7 and sys.argv[1] == "keep":
        print(keep(*sys.argv[2:]))
    elif len(sys.argv) == 4 and sys.argv[1] == "carry":
        print("carried over: %s" % ", ".join(carry(*sys.argv[2:])))
    else:
        sys.exit(__doc__)
