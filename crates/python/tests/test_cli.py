"""The ``hagfish`` command pip installs (and ``python -m hagfish``) is the program: its output
and exit codes, a signal stopping a run, two runs in one process; and the Slurm cluster of
docs/python.md writes the job script it shows (no Slurm needed: nothing is submitted)."""

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

import hagfish

BIN = Path(sys.executable).parent


def command(*arguments: str, **options) -> subprocess.CompletedProcess:
    """The installed console script with `arguments`, its output captured as text."""
    return subprocess.run([str(BIN / "hagfish"), *arguments], capture_output=True, text=True,
                          timeout=300, **options)


def test_the_installed_command_is_the_program():
    assert (BIN / "hagfish").is_file(), "pip install ./crates/python installs `hagfish`"
    version = command("--version")
    assert version.returncode == 0, version.stderr
    assert version.stdout.strip() == f"hagfish {hagfish.__version__}"
    params = command("params")
    assert params.returncode == 0, params.stderr
    assert "time_step_s" in params.stdout
    assert command("--help").returncode == 0
    # A usage mistake is clap's message and exit code 2; a mistake in a subcommand is the
    # program's `error: …` line and its exit code.
    usage = command("--no-such-option")
    assert usage.returncode == 2 and "error" in usage.stderr and usage.stdout == ""
    missing = command("run", "no_such_scenario.ron", "--out", "unused")
    assert missing.returncode == 2
    assert missing.stderr.startswith("error: ") and "no_such_scenario.ron" in missing.stderr
    module = subprocess.run([sys.executable, "-m", "hagfish", "--version"],
                            capture_output=True, text=True, timeout=300)
    assert module.returncode == 0 and module.stdout == version.stdout


@pytest.mark.parametrize("stop", [signal.SIGINT, signal.SIGTERM], ids=["SIGINT", "SIGTERM"])
def test_a_signal_stops_a_run_of_the_command_resumably(tmp_path, thesis, stop):
    out = tmp_path / "run"
    process = subprocess.Popen(
        [str(BIN / "hagfish"), "run", str(thesis), "--out", str(out), "--quiet",
         "--set", "time_step_s=0.002"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
    )
    try:
        deadline = time.monotonic() + 120
        while not (out / "checkpoint.ron").exists():
            assert process.poll() is None, process.communicate()
            assert time.monotonic() < deadline, "no checkpoint after 120 s"
            time.sleep(0.05)
        process.send_signal(stop)
        stdout, stderr = process.communicate(timeout=120)
    finally:
        process.kill()
    assert process.returncode == 130, stderr
    assert "interrupted by a signal" in stderr
    assert json.loads((out / "manifest.json").read_text())["status"] == "interrupted"


def test_the_command_line_runs_twice_in_one_process(tmp_path, thesis):
    # The second run sets its SIGINT/SIGTERM handler again (`ctrlc` allows one per process).
    # In a child interpreter: `main` takes over SIGINT from Python for the process.
    out = tmp_path / "run"
    script = (
        "import sys\nfrom hagfish import _native\n"
        f"print(_native.main(['hagfish', 'run', {str(thesis)!r}, '--out', {str(out)!r},"
        " '--quiet', '--stop-after-frames', '1']))\n"
        f"print(_native.main(['hagfish', 'run', '--resume', {str(out)!r}, '--quiet',"
        " '--stop-after-frames', '2']))\n"
    )
    child = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                           timeout=300)
    assert child.returncode == 0, child.stderr
    assert child.stdout.splitlines()[-1] == "0" and "\n0\n" in child.stdout, child.stdout
    assert "error" not in child.stderr, child.stderr
    assert json.loads((out / "manifest.json").read_text())["status"] == "interrupted"


def test_the_slurm_cluster_of_the_docs_writes_its_job_script(tmp_path, monkeypatch):
    from dask_jobqueue import SLURMCluster

    # Slurm's commands, recording any call: making the cluster must submit nothing.
    calls = tmp_path / "calls"
    for name in ["sbatch", "squeue", "scancel"]:
        fake = tmp_path / name
        fake.write_text(f"#!/bin/sh\necho {name} \"$@\" >> {calls}\nexit 1\n")
        fake.chmod(0o755)
    monkeypatch.setenv("PATH", f"{tmp_path}{os.pathsep}{os.environ['PATH']}")

    # As docs/python.md, "On a cluster with Dask" (without `cluster.scale`, which submits).
    cluster = SLURMCluster(cores=1, processes=1, memory="1GB", walltime="01:00:00")
    try:
        script = cluster.job_script()
        assert len(cluster.workers) == 0
    finally:
        cluster.close()
    lines = script.splitlines()
    assert lines[0].startswith("#!")
    for line in ["#SBATCH -n 1", "#SBATCH --cpus-per-task=1", "#SBATCH --mem=954M",
                 "#SBATCH -t 01:00:00"]:
        assert line in lines, script
    worker = [line for line in lines if "distributed.cli.dask_worker" in line]
    assert len(worker) == 1, script
    assert "--nthreads 1" in worker[0] and "tcp://" in worker[0]
    assert not calls.exists(), calls.read_text()
