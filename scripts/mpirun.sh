#!/usr/bin/env bash
# Start fdparticle (or any MPI program) on N ranks as the tests and benchmarks do:
#   bash scripts/mpirun.sh N PROGRAM [ARGS...]
# The ranks may share their cores with other work (ctest runs tests side by side, a
# workstation has other jobs), so they are not pinned to cores (the kernel moves a rank to
# whichever core is free) and a rank that waits for a message yields its core instead of
# spinning (Open MPI's mpi_yield_when_idle). More ranks than cores are allowed.
set -euo pipefail
ranks="$1"
shift
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_mpi_yield_when_idle=1
exec mpirun --oversubscribe --bind-to none -np "$ranks" "$@"
