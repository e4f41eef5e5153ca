"""pytest set-up for the Python binding's tests (tests/python): where the
package, its shared object, the corpus and the programs are.

CTest (tests/python/CMakeLists.txt) sets MESHTOPO_PYTHON_LIBRARY (the build's
libmeshtopo-python.so), MESHTOPO_CLI (its meshtopo), MESHTOPOD and
MESHTOPO_CORPUS (the build's corpus, tests/corpus and what was added); the package is
imported from lib/python of this tree unless MESHTOPO_PYTHON_PATH names
another directory (an installed one)."""
import os
import sys

import pytest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.environ.get("MESHTOPO_PYTHON_PATH", os.path.join(REPO, "lib", "python")))


def corpus_dir():
    """MESHTOPO_CORPUS (ctest sets it to the build's corpus), else the
    repository's tests/corpus."""
    return os.environ.get("MESHTOPO_CORPUS") or os.path.join(REPO, "tests", "corpus")


def corpus_meshes():
    """Names of the corpus meshes (those with a NAME.expected.json)."""
    d = corpus_dir()
    if not os.path.isdir(d):
        return []
    return sorted(n[: -len(".expected.json")] for n in os.listdir(d)
                  if n.endswith(".expected.json"))


def corpus_file(name):
    """The mesh file of a corpus mesh, as its answers name it."""
    import json
    with open(os.path.join(corpus_dir(), name + ".expected.json"), encoding="utf-8") as f:
        return os.path.join(corpus_dir(), json.load(f)["file"])


@pytest.fixture(scope="session")
def cli():
    path = os.environ.get("MESHTOPO_CLI")
    if not path:
        pytest.fail("MESHTOPO_CLI is not set: run the tests through ctest (python.*)")
    return path
