"""pytest set-up for the Python binding's tests (tests/python): where the
package, its shared object, the corpus and the programs are.

CTest (tests/python/CMakeLists.txt) sets MESHTOPO_PYTHON_LIBRARY (the build's
libmeshtopo-python.so), MESHTOPO_CLI (its meshtopo), MESHTOPOD and
MESHTOPO_CORPUS_DEFAULT (MESHTOPO_CORPUS overrides it); the package is
imported from lib/python of this tree unless MESHTOPO_PYTHON_PATH names
another directory (an installed one)."""
import os
import sys

import pytest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.environ.get("MESHTOPO_PYTHON_PATH", os.path.join(REPO, "lib", "python")))


def corpus_dir():
    """MESHTOPO_CORPUS, else the build's corpus (MESHTOPO_CORPUS_DEFAULT, set by
    ctest), else ../shared/corpus next to the repository."""
    return (os.environ.get("MESHTOPO_CORPUS") or os.environ.get("MESHTOPO_CORPUS_DEFAULT")
            or os.path.join(REPO, "..", "shared", "corpus"))


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
