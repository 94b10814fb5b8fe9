#!/bin/sh
# Make the shipped baselines (reports/baselines/SUITE.json) from a clean tree, by the gate's own
# command: each suite is run afresh and written by `mbxval check --update`. The suite is then run
# again with one BLAS and OpenMP thread instead of the machine's default and compared with what was
# just written: a cell whose status or error turns on round-off (the summation order of a threaded
# BLAS) fails that comparison, and the script exits 1 naming it, rather than ship a baseline that a
# fresh clone does not reproduce.
#
#     scripts/make_baselines.sh                # dynamics and default
#     scripts/make_baselines.sh dynamics       # one suite
#
# It takes as long as the suites, twice (the dynamics suite about 2.5 min a run on 2 cores).
set -eu
cd "$(dirname "$0")/.."
if [ -n "$(git status --porcelain --untracked-files=no)" ]; then
    echo "make_baselines: the tree has uncommitted changes; a baseline is made from a commit" >&2
    exit 2
fi
MBXVAL="${MBXVAL:-mbxval}"
scratch=$(mktemp -d "${TMPDIR:-/tmp}/mbxval-baselines.XXXXXX")
trap 'rm -rf "$scratch"' EXIT INT TERM
for name in ${*:-dynamics default}; do
    echo "== $name: the suite run afresh, its baseline written"
    "$MBXVAL" check --suite "$name" --baseline "reports/baselines/$name.json" \
        --out "$scratch/$name" --update --quiet
    echo "== $name: run again on one BLAS thread and compared with it"
    OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 MKL_NUM_THREADS=1 \
        "$MBXVAL" check --suite "$name" --baseline "reports/baselines/$name.json" \
        --out "$scratch/$name-one-thread" --quiet
done
