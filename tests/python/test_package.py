"""The package itself: its version, its public names, their docstrings, and a type stub that
covers the whole extension."""

from __future__ import annotations

import ast
import pathlib
import re

import floornav
from floornav import _floornav
from conftest import ROOT


def test_version_is_the_project_version():
    cmake = (ROOT / "CMakeLists.txt").read_text()
    version = re.search(r"project\(floornav VERSION ([0-9.]+)", cmake).group(1)
    assert floornav.__version__ == version


def test_every_public_name_exists_and_is_documented():
    for name in floornav.__all__:
        obj = getattr(floornav, name)
        if callable(obj):
            assert obj.__doc__ and len(obj.__doc__) > 20, name


def test_the_stub_declares_everything_the_extension_has():
    package = pathlib.Path(floornav.__file__).parent
    assert (package / "py.typed").exists()
    tree = ast.parse((package / "_floornav.pyi").read_text())
    declared = {n.name for n in tree.body if isinstance(n, (ast.ClassDef, ast.FunctionDef))}
    declared |= {t.id for n in tree.body if isinstance(n, ast.AnnAssign) for t in [n.target]}
    declared |= {t.id for n in tree.body if isinstance(n, ast.Assign) for t in n.targets}
    public = {n for n in dir(_floornav) if not n.startswith("__")}
    assert public - declared == set()


def test_the_attributes_the_docs_use_work_without_their_own_import():
    import subprocess
    import sys

    # floornav.chapter without `import floornav.chapter`, in a fresh interpreter.
    code = "import floornav; print(floornav.chapter.factory('hybrid') is not None)"
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert p.stdout.strip() == "True"
    params = floornav.NavigationParams()
    assert params.v0 > 0 and floornav.ControllerConfig().planner.kind == "none"
    assert floornav.ParallelEnv and floornav.Box and floornav.Dict
