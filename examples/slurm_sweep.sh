#!/usr/bin/env bash
# A sweep as a Slurm job array: each array task makes its shard of the plan; rerunning the
# array (after a time limit or a node failure) makes only the runs that have not ended, and
# resumes a cut-off run from its last frame. Collect once every task is done.
#
#   hagfish sweep plan examples/timestep_grid.ron --out $SCRATCH/sweeps/h
#   sbatch --array=1-8 examples/slurm_sweep.sh $SCRATCH/sweeps/h    # or --array=0-7: the same
#   sbatch --dependency=afterok:<array job id> --wrap "hagfish sweep collect $SCRATCH/sweeps/h"
#
# `hagfish` must be on PATH in the job: `cargo install --path . --locked` (~/.cargo/bin), or
# `pip install ./crates/python` in a virtual environment the job activates (README.md).
#
# Each run is single-threaded: one CPU per task. A 30 s thesis run takes ≈ 1–3 s of CPU and
# ≈ 10–50 MB on disk (without pictures: `hagfish render DIR` draws them later).
#SBATCH --job-name=hagfish-sweep
#SBATCH --cpus-per-task=1
#SBATCH --mem=1G
#SBATCH --time=01:00:00
#SBATCH --output=hagfish-sweep-%A_%a.log
set -euo pipefail
folder="${1:?usage: sbatch --array=1-N slurm_sweep.sh SWEEP_FOLDER}"
# Shards count from 1; the array may be numbered from 0 or 1 (or any first index).
shard=$((SLURM_ARRAY_TASK_ID - SLURM_ARRAY_TASK_MIN + 1))
hagfish sweep run "$folder" --shard "${shard}/${SLURM_ARRAY_TASK_COUNT}"
