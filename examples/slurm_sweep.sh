#!/usr/bin/env bash
# A sweep as a Slurm job array: each array task makes its shard of the plan; rerunning the
# array (after a time limit or a node failure) makes only the runs that have not ended, and
# resumes a cut-off run from its last frame. Collect once every task is done.
#
#   hagfish sweep plan examples/timestep_grid.ron --out $SCRATCH/sweeps/h
#   sbatch --array=0-7 examples/slurm_sweep.sh $SCRATCH/sweeps/h
#   sbatch --dependency=afterok:<array job id> --wrap "hagfish sweep collect $SCRATCH/sweeps/h"
#
# Each run is single-threaded: one CPU per task. A 30 s thesis run takes ≈ 1–3 s of CPU and
# ≈ 10–50 MB on disk (without pictures: `hagfish render DIR` draws them later).
#SBATCH --job-name=hagfish-sweep
#SBATCH --cpus-per-task=1
#SBATCH --mem=1G
#SBATCH --time=01:00:00
#SBATCH --output=hagfish-sweep-%A_%a.log
set -euo pipefail
folder="${1:?usage: sbatch --array=0-(N-1) slurm_sweep.sh SWEEP_FOLDER}"
hagfish sweep run "$folder" --shard "${SLURM_ARRAY_TASK_ID}/${SLURM_ARRAY_TASK_COUNT}"
