"""Installing from a checkout puts a copy of the built libpmech.so inside the package, so that the
installed package works without the checkout: from $PMECH_BUILD_DIR, else from ../build (make build).
Without a built library the package is installed alone and finds an installed one at import
(make install, pkg-config, or $PMECH_LIBRARY)."""
import os
import shutil

from setuptools import setup
from setuptools.command.build_py import build_py


class BuildWithLibrary(build_py):
    def run(self):
        super().run()
        here = os.path.dirname(os.path.abspath(__file__))
        build = os.environ.get("PMECH_BUILD_DIR", os.path.join(here, os.pardir, "build"))
        lib = os.path.join(build, "libpmech.so")
        if os.path.exists(lib):
            dest = os.path.join(self.build_lib, "pmech", "libpmech.so")
            shutil.copyfile(os.path.realpath(lib), dest)
            print("pmech: bundled %s" % os.path.realpath(lib))
        else:
            print("pmech: no %s; the package will look for an installed libpmech.so" % lib)


setup(cmdclass={"build_py": BuildWithLibrary})
