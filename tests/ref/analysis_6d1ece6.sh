#!/bin/sh
# analysis_6d1ece6.sh: how tests/fixtures/analysis_6d1ece6.csv was made --
# the analysis beyond the paper as the code before the engine (commit
# 6d1ece6, issue 11) computed it: `compare --fit exact` on every CURET
# sample and every model but WNO-R (whose quadrature rule the engine
# changed on purpose, doc/methods.md §7), default folds and seed. The
# columns kept are those tests/fit/test_before.c compares.
# Usage: tests/ref/analysis_6d1ece6.sh CURET_DIR > analysis_6d1ece6.csv
set -eu
data=${1:?CURET folder}
work=$(mktemp -d)
git worktree add --detach "$work/src" 6d1ece6 >/dev/null
cmake -S "$work/src" -B "$work/build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$work/build" --target brdffit -j2 >/dev/null
"$work/build/brdffit" compare --data "$data" --fit exact --samples all \
    --models all --out "$work/out" -q
python3 - "$work/out/fits.csv" <<'PY'
import csv, sys
cols = ["sample", "model", "parameter", "refined_value", "refined_lse",
        "ci_low", "ci_high", "aic", "bic", "cv"]
w = csv.writer(sys.stdout, lineterminator="\n")
w.writerow(cols)
for r in csv.DictReader(open(sys.argv[1])):
    if r["model"] != "WNO-R":
        w.writerow([r[c] for c in cols])
PY
git worktree remove --force "$work/src"
rm -rf "$work"
