"""Shared fixtures of the ablmg Python tests (run by CTest as python.pytest, label python).

ctest sets PYTHONPATH to build/python, ABLMG_BIN to the ablmg program and ABLMG_SOURCE_DIR
to the repository; run by hand:
  PYTHONPATH=build/python ABLMG_BIN=build/bin/ablmg /usr/bin/python3 -m pytest python/tests
"""
import os
import pathlib

import numpy as np
import pytest

import ablmg

SOURCE_DIR = pathlib.Path(os.environ.get("ABLMG_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
DATA = SOURCE_DIR / "tests" / "data"


@pytest.fixture(scope="session")
def ablmg_bin():
    path = pathlib.Path(os.environ.get("ABLMG_BIN", SOURCE_DIR / "build" / "bin" / "ablmg"))
    if not path.exists():
        pytest.skip(f"{path} not built")
    return path


@pytest.fixture(scope="session")
def square_mesh():
    """A unit-square mesh of about 500 vertices, boundary refs 1-4."""
    return ablmg.mesh(ablmg.Domain.rectangle(0, 0, 1, 1), 0.05)


@pytest.fixture(scope="session")
def graded_metric(square_mesh):
    """An anisotropic metric per vertex of square_mesh: a layer along x = 0.5."""
    x = square_mesh.points[:, 0]
    h1 = np.full_like(x, 0.08)
    h2 = 0.01 + 0.15 * np.abs(x - 0.5)
    return np.stack([1 / h2**2, np.zeros_like(x), 1 / h1**2], axis=1)
