#!/bin/sh
# main_job.sh: measures the main job as a new user meets it -- `make run`
# from a fresh clone (configure, build of the library and the CLI, the
# report), then the report step alone (the same command, 3 times, the
# median) and the sizes of what it writes. Never part of the tests.
#
#   bench/main_job.sh [CURET_DIR]     (default ../shared/data/curet)
#
# The clone is made from this checkout's HEAD (git clone --local) in a
# temporary folder; CURET's files are read in place.
set -eu

here=$(cd "$(dirname "$0")/.." && pwd)
curet=$(cd "${1:-$here/../shared/data/curet}" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

now() { date +%s.%N; }
elapsed() { echo "$2 - $1" | bc; }

git clone -q --local "$here" "$tmp/clone"
cd "$tmp/clone"
load=$(cut -d ' ' -f 1-3 /proc/loadavg)
t0=$(now)
make run CURET="$curet" OUT="$tmp/out" >/dev/null 2>"$tmp/err" || {
    cat "$tmp/err" >&2
    exit 1
}
t1=$(now)
run=$(elapsed "$t0" "$t1")

# the report step alone: the command make run ran
times=""
for _ in 1 2 3; do
    rm -rf "$tmp/out2"
    t0=$(now)
    build/brdffit report --data "$curet" --samples paper --stats \
        --on-params data/oren_nayar_params.tsv --out "$tmp/out2" \
        --threads 0 -q
    t1=$(now)
    times="$times $(elapsed "$t0" "$t1")"
done
# shellcheck disable=SC2086 # the times, one per word
median=$(printf '%s\n' $times | sort -n | sed -n 2p)

size() { du -cb "$@" 2>/dev/null | tail -n 1 | cut -f 1; }
kb() { echo "scale=0; $1 / 1024" | bc; }
f="$tmp/out/figures"
echo "machine: $(nproc) cores, load before the run: $load"
echo "make run from a fresh clone (configure + build + report): ${run} s"
echo "report step alone (median of 3):${times} -> ${median} s"
echo "output: $(kb "$(size "$tmp/out")") KB in $(find "$tmp/out" -type f | wc -l) files"
for ext in png pdf; do
    set -- "$f"/*."$ext"
    echo "  $ext: $# files, $(kb "$(size "$@")") KB"
done
for kind in fig2b wins scatter delta_bic forest plane polar profile; do
    set -- "$f"/"$kind"*.png
    [ -f "$1" ] || continue
    echo "  $kind: $# figure(s), PNG $(kb "$(size "$@")") KB," \
        "PDF $(kb "$(size "$f"/"$kind"*.pdf)") KB"
done
# SVG on request: the same figures once more, SVG only
build/brdffit report --data "$curet" --samples paper --stats \
    --on-params data/oren_nayar_params.tsv --out "$tmp/svg" --threads 0 \
    --format svg -q
set -- "$tmp/svg/figures"/*.svg
echo "  svg (--format svg): $# files, $(kb "$(size "$@")") KB"
