"""Packaging beyond pyproject.toml: the suite's scenes/ and references/ installed as package data where they
are in the repository (the packages mcval_suite.scenes and mcval_suite.references map onto those folders, which
harness/project.py finds), and the scenes' meshes, which the repository does not hold, generated into the
built package (scenes/generate_meshes.py, numpy only, about a second)."""
import importlib.util
from pathlib import Path

from setuptools import find_packages, setup
from setuptools.command.build_py import build_py

HERE = Path(__file__).resolve().parent
SUITE = {"mcval_suite.scenes": "scenes", "mcval_suite.references": "references"}


def data_packages() -> dict[str, list[str]]:
    """Every folder of scenes/ and references/ as a package of its own files (setuptools warns of a data
    folder that is not listed as a package)."""
    found = {}
    for name, folder in SUITE.items():
        root = HERE / folder
        for sub in [root, *sorted(p for p in root.rglob("*") if p.is_dir() and p.name != "__pycache__")]:
            found[".".join([name, *sub.relative_to(root).parts])] = ["*"]
    return found


class BuildWithMeshes(build_py):
    """build_py, then the meshes the scene files name, into the built copy of scenes/ (an editable install
    reads scenes/ in place, where `make build` writes them)."""

    def run(self) -> None:
        super().run()
        if getattr(self, "editable_mode", False):
            return
        spec = importlib.util.spec_from_file_location("generate_meshes", HERE / "scenes" / "generate_meshes.py")
        generator = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(generator)
        generator.generate(Path(self.build_lib) / "mcval_suite" / "scenes" / "meshes")


setup(
    packages=find_packages(include=["harness", "harness.*"]) + list(data_packages()),
    package_dir=SUITE,
    package_data=data_packages(),
    cmdclass={"build_py": BuildWithMeshes},
    # build/ is CMake's (the Makefile's C++ build): the package is built in a folder of its own inside it.
    options={"build": {"build_base": "build/python-package"}},
)
