"""Shared set-up of the deck tests: lmprun on the path, and the tiny bag filled once per module."""
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
import lmprun  # noqa: E402


@pytest.fixture(scope="module")
def tiny_filled(tmp_path_factory):
    """A folder with the tiny bag (lmprun.TINY_BAG) made and filled: bag.data, fill.data, logs
    (a copy of the suite's shared fill when ctest made one: fixture "tiny")."""
    return lmprun.filled_bag(tmp_path_factory.mktemp("tinybag"))
