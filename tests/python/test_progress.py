"""The launcher's progress lines (launcher/tbagsrun/progress.py) from the decks' thermo output."""
import sys
import threading
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "launcher"))
from tbagsrun import progress  # noqa: E402

COMPRESSION = """   Step          Time         v_Fmeas          v_w          f_top[9]        v_conv        CPULeft    
    332600   0.4989         1778.8178     -0.009978       3453           0              0            
    334000   0.501          1802.0317     -0.01002        3473           0              4583.7927    
"""
# in.shear's thermo (a trends run), its last row cut by the read
SHEAR = """   Step          Time          v_done          v_u            v_w            v_S          v_Fmeas        v_broken       CPULeft    
     66000  0.099 0 0 -0.0019142 10.175 212.08 0 0
     66670  0.10001 0.201 1.005e-05 -0.0019165 13.262 212.12 0 280.01
    386686  0.58003 96.206 0.0048103 -0.0018868 453.16 212.35 0 10.385
    393353  0.59003 98.206 0.0049103 -0.0018691 463.1 212.18 0 4.9068
    40001  0.6
"""
CYCLIC = """   Step          Time          v_pct          v_uc           v_w            v_S          v_Fmeas        v_broken        v_eta     
     10000  0.015 12.5 0.00025 -0.0014 88.1 317.2 0 95.5
"""


def test_status_of_each_deck():
    assert progress.status(COMPRESSION.splitlines()) == "compressing: F_v 1802 N at step 334000"
    assert progress.status((COMPRESSION + SHEAR).splitlines()) == \
        "98 % of the shear (u 4.91 mm), about 5 s left"
    assert progress.status(CYCLIC.splitlines()) == "12 % of the cycles, about 1.6 h left"
    assert progress.status(["LAMMPS (4 Feb 2025)", "Loop time"]) is None
    assert progress.duration(4583.8) == "1.3 h" and progress.duration(280) == "5 min" and progress.duration(95) == "95 s"


def test_watch_says_changes_while_the_block_runs(tmp_path):
    screen = tmp_path / "screen.shear.txt"
    screen.write_text(COMPRESSION)
    said = []
    with progress.Watch(screen, "shear in F5500", 0.05, said.append):
        time.sleep(0.3)
        screen.write_text(COMPRESSION + SHEAR)
        time.sleep(0.3)
    n = len(said)
    time.sleep(0.2)
    assert said == ["  shear in F5500: compressing: F_v 1802 N at step 334000",
                    "  shear in F5500: 98 % of the shear (u 4.91 mm), about 5 s left"]
    assert len(said) == n and threading.active_count() == 1    # stopped with the block
    with progress.Watch(screen, "x", 0, said.append) as w:    # 0: none
        assert w.thread is None


def shear_row(step, pct, left):
    return "%d 0.1 %g 0 -0.0019 10.0 212.0 0 %g\n" % (step, pct, left)


def test_first_estimate_is_measured_and_lines_are_ten_percent_apart(tmp_path):
    """LAMMPS's first row says 0 s left: the line says 'estimating', not 'about 0 min left'
    (be13c81 on the demo); then the time left comes from the stage's own rate, and lines are
    10 % of the stage apart even when polled often."""
    screen = tmp_path / "screen.shear.txt"
    head = SHEAR.splitlines()[0] + "\n"
    screen.write_text(head + shear_row(1, 0.2, 0))
    now = [0.0]
    said = []
    w = progress.Watch(screen, "shear", 0.01, said.append, clock=lambda: now[0])
    with w:
        now[0] = 1.0
        time.sleep(0.1)
        for k, pct in enumerate((3, 6, 12, 14, 25), start=1):
            now[0] = 10.0 * k    # 10 s per row
            screen.write_text(head + shear_row(100 * k, pct, 0 if pct < 12 else 999))
            time.sleep(0.1)
    assert said[0] == "  shear: 0 % of the shear (u 0.00 mm), time left: estimating"
    pcts = [float(line.split(": ")[1].split(" %")[0]) for line in said]
    assert all(b - a >= 10 for a, b in zip(pcts, pcts[1:])), said
    # at 12 %: (12 - 0.2) % in 29 s -> 88 % in 216 s, about 4 min (not LAMMPS's 999 s)
    assert "  shear: 12 % of the shear (u 0.00 mm), about 4 min left" in said, said


def test_a_slow_stage_says_its_progress_every_ten_minutes(tmp_path):
    """A stage of hours (the paper run: a thermo row per 2 % of the shear, about 8 min apart)
    gets a line when 10 min have passed without one, though it moved less than 10 %."""
    screen = tmp_path / "screen.shear.txt"
    head = SHEAR.splitlines()[0] + "\n"
    screen.write_text(head + shear_row(1, 20, 0))
    now = [0.0]
    said = []
    with progress.Watch(screen, "shear", 0.01, said.append, clock=lambda: now[0]):
        time.sleep(0.1)
        for k in range(1, 6):
            now[0] = 480.0 * k    # 2 % per 8 min
            screen.write_text(head + shear_row(100 * k, 20 + 2 * k, 0))
            time.sleep(0.1)
    pcts = [float(line.split(": ")[1].split(" %")[0]) for line in said]
    assert pcts == [22, 26, 30], said    # at 8, 24 and 40 min (8 min after a line: too soon)
