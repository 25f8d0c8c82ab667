"""The independent programs the export tests open files with, or a visible skip naming
what to install (``scripts/test.sh`` installs all of them)."""

from __future__ import annotations

import importlib
import json
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
GLTF_VALIDATOR = ROOT / ".cache" / "npm" / "node_modules" / "gltf-validator"


def module(name: str, install: str):
    """Import ``name`` or skip the test saying how to install it."""
    try:
        return importlib.import_module(name)
    except ImportError:
        pytest.skip(f"{name} is not installed: {install}")


def ocp():
    return module("OCP", "pip install 'gearcoupling[step]' (cadquery-ocp-novtk)")


def ccx() -> str:
    path = shutil.which("ccx")
    if path is None:
        pytest.skip("CalculiX ccx is not installed: apt-get install -y calculix-ccx "
                    "(scripts/test.sh does it as root)")
    return path


def gltf_validate(path: Path) -> dict:
    """Khronos glTF validator's report of a GLB file (npm ``gltf-validator``)."""
    node = shutil.which("node")
    if node is None or not GLTF_VALIDATOR.is_dir():
        pytest.skip("glTF validator missing: npm install --prefix .cache/npm gltf-validator "
                    "(scripts/test.sh does it)")
    script = ("const v = require(process.argv[1]); const fs = require('fs');"
              "v.validateBytes(new Uint8Array(fs.readFileSync(process.argv[2])))"
              ".then(r => console.log(JSON.stringify(r)))"
              ".catch(e => { console.error(e); process.exit(1); });")
    done = subprocess.run([node, "-e", script, str(GLTF_VALIDATOR), str(path)],
                          capture_output=True, text=True, check=True, timeout=120)
    return json.loads(done.stdout)
