import os

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
DATA = os.path.join(ROOT, "tests", "data")


@pytest.fixture
def grid():
    import rtlacam
    return rtlacam.load_map(os.path.join(DATA, "planner", "random-32-32-20.map"))


@pytest.fixture
def scen():
    return os.path.join(DATA, "planner", "random-32-32-20-random-1.scen")


@pytest.fixture
def weights():
    return os.path.join(ROOT, "policy", "models", "random-32-32-20.bin")
