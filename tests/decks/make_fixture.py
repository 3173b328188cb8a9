"""A shared product of the deck tests, made once per ctest run (FIXTURES_SETUP in
tests/CMakeLists.txt) into OUT/NAME: "tiny" the tiny bag filled (lmprun.filled_bag copies it),
"demo" the main job's bag, fill and shear (lmprun.demo reads it). Usage: make_fixture.py NAME OUT"""
import shutil
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import lmprun  # noqa: E402

name, out = sys.argv[1], Path(sys.argv[2]) / sys.argv[1]
shutil.rmtree(out, ignore_errors=True)
if name == "tiny":
    lmprun.bag_and_fill(out)
elif name == "demo":
    lmprun.demo_run(out)
else:
    sys.exit("make_fixture.py: unknown fixture %s (tiny, demo)" % name)
(out / ".done").touch()
print("fixture %s made in %s" % (name, out))
