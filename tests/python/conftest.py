# Shared set-up of the Python module's tests: where the command line and the sources are (CTest
# sets CAUSTICA_EXE and CAUSTICA_SOURCE_DIR, and PYTHONPATH to the module's folder).
import os
import pathlib

import pytest

SOURCE = pathlib.Path(os.environ.get("CAUSTICA_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
EXE = os.environ.get("CAUSTICA_EXE", str(SOURCE / "build" / "caustica"))


@pytest.fixture
def source():
    return SOURCE


@pytest.fixture
def exe():
    return EXE


@pytest.fixture
def tiny(source):
    return source / "tests" / "data" / "tiny.json"
