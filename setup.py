"""pip's build of the Python package: CMake builds the module _linkbox (the library linked in)
into the wheel, beside the pure-Python package python/linkbox. Offline, from Debian's packages
only (.ci/install):

    python3 -m venv --system-site-packages .venv
    .venv/bin/pip install --no-build-isolation .
"""
import os
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        out = os.path.dirname(os.path.abspath(self.get_ext_fullpath(ext.name)))
        build = os.path.join(os.path.abspath(self.build_temp), "cmake")
        # Only the module is built: the executable's static archives are not needed.
        subprocess.check_call(["cmake", "-S", ROOT, "-B", build, "-DCMAKE_BUILD_TYPE=Release", "-DLINKBOX_PYTHON=ON",
                               "-DLINKBOX_STATIC_DEPS=OFF", "-DPython3_EXECUTABLE=" + sys.executable,
                               "-DLINKBOX_PYTHON_OUTPUT_DIR=" + out])
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        subprocess.check_call(["cmake", "--build", build, "--target", "_linkbox", "-j", jobs])


setup(
    name="linkbox",
    version="0.3.0",
    description="Verified position analysis of linkages and polynomial systems by interval branch-and-prune",
    license="GPL-3.0",
    python_requires=">=3.9",
    packages=["linkbox"],
    package_dir={"": "python"},
    ext_modules=[Extension("_linkbox", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    install_requires=["numpy"],
    extras_require={"dataframes": ["pandas"], "plots": ["matplotlib"]},
    zip_safe=False,
)
