"""pip install --no-build-isolation ./lib/python: the meshtopo package with its
shared object libmeshtopo-python.so, built by CMake from the source tree this
file is in (cmake, a C compiler and meshtopo's build dependencies are needed,
no package index). MESHTOPO_PYTHON_LIBRARY set to a built
libmeshtopo-python.so installs that one instead of building."""
import os
import shutil
import subprocess

from setuptools import setup
from setuptools.command.build_py import build_py
from setuptools.dist import Distribution

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.dirname(os.path.dirname(HERE))
LIBRARY = "libmeshtopo-python.so"


def build_library(build_temp):
    """Configures and builds the meshtopo_python target; returns the .so's path."""
    build_dir = os.path.join(os.path.abspath(build_temp), "cmake")
    subprocess.check_call(["cmake", "-S", SOURCE, "-B", build_dir, "-DCMAKE_BUILD_TYPE=Release",
                           "-DMESHTOPO_BUILD_TESTS=OFF", "-DMESHTOPO_BUILD_BENCH=OFF",
                           "-DMESHTOPO_WERROR=OFF"])
    subprocess.check_call(["cmake", "--build", build_dir, "--target", "meshtopo_python",
                           "--parallel", str(os.cpu_count() or 2)])
    return os.path.join(build_dir, "lib", "python", LIBRARY)


class BuildWithLibrary(build_py):
    """build_py that also puts libmeshtopo-python.so into the package."""

    def run(self):
        super().run()
        library = os.environ.get("MESHTOPO_PYTHON_LIBRARY")
        if not library:
            temp = self.get_finalized_command("build").build_temp
            library = build_library(temp)
        target = os.path.join(self.build_lib, "meshtopo", LIBRARY)
        shutil.copyfile(library, target)
        os.chmod(target, 0o755)


class BinaryDistribution(Distribution):
    """The package holds a shared object: a platform-specific wheel."""

    def has_ext_modules(self):
        return True


setup(
    name="meshtopo",
    version="0.1.0",
    description="Mesh topology for robots: half-edge meshes, defects and adjacency from numpy "
                "face lists, and a client of the meshtopod LCM service",
    packages=["meshtopo"],
    python_requires=">=3.9",
    install_requires=["numpy"],
    cmdclass={"build_py": BuildWithLibrary},
    distclass=BinaryDistribution,
    zip_safe=False,
)
