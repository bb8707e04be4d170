#!/bin/sh
# run.sh: runs every libFuzzer target of a fuzz build for a bounded time,
# JOBS at a time (one core each; default: the number of cores), and prints
# one summary line per target, in the targets' order, with its executions
# and executions per second. Fails if any target finds a crash, leak,
# sanitizer report, timeout or out-of-memory; libFuzzer then leaves the
# input in BUILD/fuzz-artifacts/ and prints how to reproduce it (the
# failing target's log tail is printed).
#
#   fuzz/run.sh BUILD SECONDS CURET_DIR REFERENCE_DIR [MAX_LEN [JOBS]]
#
# The working corpus (BUILD/fuzz-corpus/<target>) grows across runs; the
# seeds (BUILD/fuzz-seeds/<target>) are rebuilt from the real files.
set -eu

build=$1
seconds=$2
curet=$3
reference=$4
max_len=${5:-4096}
jobs=${6:-$(nproc 2>/dev/null || echo 1)}
here=$(dirname "$0")

# Per-input limits: a loader must finish any input in well under a second
# and never needs much memory (lines are capped at 1 MiB).
timeout=10
rss_limit_mb=1024

# run_one EXE: fuzzes EXE, writes its summary line (or FAILED) to
# BUILD/fuzz-NAME.verdict and its output to BUILD/fuzz-NAME.log.
run_one() {
    exe=$1
    name=$(basename "$exe")
    corpus=$build/fuzz-corpus/$name
    log=$build/fuzz-$name.log
    verdict=$build/fuzz-$name.verdict
    # a target added without seeds in seeds.sh starts from an empty corpus
    mkdir -p "$corpus" "$build/fuzz-seeds/$name"
    if ! "$exe" -max_total_time="$seconds" -max_len="$max_len" \
            -timeout="$timeout" -rss_limit_mb="$rss_limit_mb" \
            -print_final_stats=1 \
            -artifact_prefix="$build/fuzz-artifacts/$name-" \
            "$corpus" "$build/fuzz-seeds/$name" > "$log" 2>&1; then
        echo "fuzz: $name FAILED (log: $log)" > "$verdict"
        return 0
    fi
    execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
    rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log")
    units=$(ls "$corpus" | wc -l)
    echo "fuzz: $name ok: $execs executions in ${seconds} s ($rate exec/s), corpus $units inputs" > "$verdict"
}

# JOBS at a time, each started as soon as one ends (xargs -P), each one by
# this script again (BF_FUZZ_ONE=1: run_one of its seventh argument).
if [ "${BF_FUZZ_ONE:-}" = 1 ]; then
    run_one "$7"
    exit 0
fi

"$here/seeds.sh" "$curet" "$reference" "$build/fuzz-seeds"
mkdir -p "$build/fuzz-artifacts"
rm -f "$build"/fuzz-*.verdict
for exe in "$build"/fuzz/fuzz_*; do
    [ -x "$exe" ] && printf '%s\n' "$exe"
done | BF_FUZZ_ONE=1 xargs -P "$jobs" -I{} \
    sh "$0" "$build" "$seconds" "$curet" "$reference" "$max_len" 1 {}

status=0
for exe in "$build"/fuzz/fuzz_*; do
    [ -x "$exe" ] || continue
    name=$(basename "$exe")
    verdict=$build/fuzz-$name.verdict
    if [ ! -f "$verdict" ]; then
        echo "fuzz: $name gave no verdict" >&2
        status=1
    elif grep -q FAILED "$verdict"; then
        tail -n 40 "$build/fuzz-$name.log" >&2
        cat "$verdict" >&2
        status=1
    else
        cat "$verdict"
    fi
    rm -f "$verdict"
done
exit $status
