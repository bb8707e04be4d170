#!/bin/sh
# run.sh: runs every libFuzzer target of a fuzz build for a bounded time,
# one after the other (one core each), and prints one summary line per
# target with its executions and executions per second. Fails on the first
# crash, leak, sanitizer report, timeout or out-of-memory; libFuzzer then
# leaves the input in BUILD/fuzz-artifacts/ and prints how to reproduce it.
#
#   fuzz/run.sh BUILD SECONDS CURET_DIR REFERENCE_DIR [MAX_LEN]
#
# The working corpus (BUILD/fuzz-corpus/<target>) grows across runs; the
# seeds (BUILD/fuzz-seeds/<target>) are rebuilt from the real files.
set -eu

build=$1
seconds=$2
curet=$3
reference=$4
max_len=${5:-4096}
here=$(dirname "$0")

# Per-input limits: a loader must finish any input in well under a second
# and never needs much memory (lines are capped at 1 MiB).
timeout=10
rss_limit_mb=1024

"$here/seeds.sh" "$curet" "$reference" "$build/fuzz-seeds"
mkdir -p "$build/fuzz-artifacts"
for exe in "$build"/fuzz/fuzz_*; do
    [ -x "$exe" ] || continue
    name=$(basename "$exe")
    corpus=$build/fuzz-corpus/$name
    log=$build/fuzz-$name.log
    # a target added without seeds in seeds.sh starts from an empty corpus
    mkdir -p "$corpus" "$build/fuzz-seeds/$name"
    if ! "$exe" -max_total_time="$seconds" -max_len="$max_len" \
            -timeout="$timeout" -rss_limit_mb="$rss_limit_mb" \
            -print_final_stats=1 \
            -artifact_prefix="$build/fuzz-artifacts/$name-" \
            "$corpus" "$build/fuzz-seeds/$name" > "$log" 2>&1; then
        tail -n 40 "$log" >&2
        echo "fuzz: $name FAILED (log: $log)" >&2
        exit 1
    fi
    execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
    rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log")
    units=$(ls "$corpus" | wc -l)
    echo "fuzz: $name ok: $execs executions in ${seconds} s ($rate exec/s), corpus $units inputs"
done
