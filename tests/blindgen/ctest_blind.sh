#!/usr/bin/env bash
# ctest_blind.sh RTB OUTDIR -- the blind generator's cases whose verdicts its
# effect definitions changed (a Mullins loss on the whole material, a tanh
# softening that parsimony gave to a degressive cubic), plain data, and three
# of seed 5 that session 19's changes named right: a dashpot behind a small
# displacement noise (`delay` before the stage-0 filter threshold), a slack
# strip whose baseline switched the cell chain off (`mullins` before the
# STS restart of collapsed joint fits), and a Mullins loss with a force delay
# (`unexplained` before the third pair lead), and two of seed 10 that
# session 27's changes named right: a relaxation spectrum that parsimony
# gave to a dashpot, and a dashpot beside a cubic spring that the RT core
# absorbed (the cubic only), through `rtb diagnose`: every case named
# right, no wrong word. Exit 77 (ctest: skipped)
# without numpy and scipy (python3-numpy, python3-scipy; `make deps` installs them).
set -u
rtb=$1
out=$2
here=$(cd "$(dirname "$0")" && pwd)
py=/usr/bin/python3
if ! "$py" -c 'import numpy, scipy' 2>/dev/null; then
  echo "SKIP: /usr/bin/python3 has no numpy or scipy (Debian python3-numpy, python3-scipy)"
  exit 77
fi
rm -rf "$out"
bash "$here/run_blind.sh" --build "$(dirname "$rtb")" --out "$out" --timeout 300 \
  --cases "none:1 mullins:1 softening:2 viscous:5 slack:5 mullins,delay:5 \
  relaxation_spectrum:10 viscous,cubic_stiffness:10" || exit 1
"$py" "$here/score_blind.py" --strict "$out"
