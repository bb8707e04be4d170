#!/bin/sh
# glossy_peer.sh: the scale-keeping fits (SPEC §10, objective ngan) of the
# five Cornell paints against the numpy/scipy peer
# ../shared/peers/glossy_peer.py (24-start least_squares), E and wall time
# per file, channel mean as the peer fits it. Run from the repository root
# after a build: sh bench/glossy_peer.sh [build] [python3 with scipy]
# Prints one TSV row per file and model: file, model, E_brdffit, E_peer,
# t_brdffit_s, t_peer_s (the peer's time is its whole run over its models).
set -eu
BUILD=${1:-build}
PY=${2:-/usr/bin/python3}
DATA=../shared/data/cornell-pbrt-v2
PEER=../shared/peers/glossy_peer.py
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
MODELS=LAMBERT,LAMBERT+GGX,LAMBERT+BECKMANN,LAMBERT+WARD,LAMBERT+WARD-DUER
printf 'file\tmodel\tE_brdffit\tE_peer\tt_brdffit_s\tt_peer_s\n'
for f in "$DATA"/*.brdf; do
    b=$(basename "$f" .brdf)
    t0=$(date +%s.%N)
    "$PY" "$PEER" "$f" > "$OUT/$b.peer"
    t1=$(date +%s.%N)
    "$BUILD/brdffit" compare --models "$MODELS" --fit exact --objective ngan \
        --folds 0 --quiet --out "$OUT/$b" "$f"
    t2=$(date +%s.%N)
    for m in $(echo "$MODELS" | tr ',' ' '); do
        # fits.csv: the model's rho_d row (LAMBERT's free scale, a
        # composite's first parameter) holds E in column lse
        e=$(awk -F, -v m="$m" 'NR > 1 && /rho_d/ {
                for (i = 1; i <= NF; i++) if ($i == m) print $(i + 4) }' \
            "$OUT/$b/fits.csv" | head -1)
        p=$(awk -v m="$m" '$1 == m { print $2 }' "$OUT/$b.peer")
        printf '%s\t%s\t%s\t%s\t%.3f\t%.2f\n' "$b" "$m" "$e" "$p" \
            "$(echo "$t2 - $t1" | bc)" "$(echo "$t1 - $t0" | bc)"
    done
done
