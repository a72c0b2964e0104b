"""Shared fixtures: the CLI, a simulated office (with the simulator's truth) aligned once by the
CLI and once from Python with the same seed and options."""

import json
import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
# Fewer models and folds than the defaults keep the two alignments of the session short; the CLI
# and Python get the same file.
FAST_OPTIONS = {"align": {"models": {
    "models": ["gt", "gp", "tps", "dt", "auto"],
    "mapping": {"auto_select": {"candidates": ["gt", "gp", "tps", "dt"]}}}}}


def run_cli(*args, check=True):
    result = subprocess.run([os.environ.get("FLOORGRID_CLI", str(ROOT / "build" / "floorgrid")),
                             *map(str, args)], capture_output=True, text=True)
    if check and result.returncode != 0:
        raise AssertionError(f"floorgrid {' '.join(map(str, args))} exited "
                             f"{result.returncode}:\n{result.stdout}\n{result.stderr}")
    return result


@pytest.fixture(scope="session")
def workdir(tmp_path_factory):
    folder = os.environ.get("FLOORGRID_TEST_DIR")
    if folder:
        path = Path(folder)
        path.mkdir(parents=True, exist_ok=True)
        return path
    return tmp_path_factory.mktemp("floorgrid")


@pytest.fixture(scope="session")
def office(workdir):
    """A simulated office (seed 1) with its exact truth (truth.json)."""
    out = workdir / "office"
    run_cli("simulate", "--preset", "office", "--seed", "1", "--out", out)
    return out


@pytest.fixture(scope="session")
def fast_config(workdir):
    path = workdir / "fast-options.yaml"
    path.write_text(json.dumps(FAST_OPTIONS))
    return path


@pytest.fixture(scope="session")
def cli_alignment(office, workdir, fast_config):
    """`floorgrid align` on the office: its output folder."""
    out = workdir / "cli-align"
    run_cli("align", office, "--out", out, "--seed", "1", "--config", fast_config)
    return out


@pytest.fixture(scope="session")
def python_alignment(office, workdir, fast_config):
    """floorgrid.align on the office with the CLI's seed and options, and its progress calls."""
    import floorgrid
    calls = []
    result = floorgrid.align(office, out=workdir / "py-align", seed=1, config=fast_config,
                             progress=lambda *p: calls.append(p))
    return result, calls
