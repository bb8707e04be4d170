#!/bin/sh
# seeds.sh: builds the seed corpus of the fuzz targets from the real CURET
# files, read in place (never copied into the repository), plus a few small
# hand-made inputs. The seeds go to OUT/<target>/, one file per seed.
#
#   fuzz/seeds.sh CURET_DIR REFERENCE_DIR OUT
set -eu

curet=$1
reference=$2
out=$3

for f in "$curet/table.txt" "$curet/abrdf.dat" "$curet/samples.tsv" \
         "$reference/oren_nayar_params.tsv"; do
    if [ ! -r "$f" ]; then
        echo "seeds.sh: $f is missing (the seeds come from the real files)" >&2
        exit 1
    fi
done

rm -rf "$out"
mkdir -p "$out/fuzz_table" "$out/fuzz_brdf" "$out/fuzz_sample_table" \
         "$out/fuzz_names"

# Configuration table: whole file (CRLF, no final newline), its first rows,
# an LF copy, one with a UTF-8 byte order mark.
t=$out/fuzz_table
cp "$curet/table.txt" "$t/table-full"
head -n 12 "$curet/table.txt" > "$t/table-head"
head -n 12 "$curet/table.txt" | tr -d '\r' > "$t/table-lf"
{ printf '\357\273\277'; head -n 3 "$curet/table.txt"; } > "$t/table-bom"
printf '1 0.2 0.0 0.3 1.0\n2 1.5707963268 2.0 0.6 0.5\n' > "$t/table-grazing"

# BRDF rows: the first rows of abrdf.dat at full width (205 values), the
# same rows cut to 8 values, and rows out of order.
b=$out/fuzz_brdf
head -n 2 "$curet/abrdf.dat" > "$b/abrdf-head"
head -n 4 "$curet/abrdf.dat" |
    awk '{ for (i = 1; i <= 9; i++) printf "%s%s", $i, (i < 9 ? " " : "\n") }' \
    > "$b/abrdf-narrow"
printf '2 0.25 0.35 0.05\n1 0.30 -0.01 0.10\n3 1e-3 2.5E+0 0\n' \
    > "$b/brdf-unordered"

# Per-sample tables: the study's Oren-Nayar parameters, an op.dat-like
# 4-column file, a refractive index file.
s=$out/fuzz_sample_table
cp "$reference/oren_nayar_params.tsv" "$s/on-params"
printf '1 0.387 0.415 0.52\n2\t0.380\t0.577\t0.61\n' > "$s/op-dat"
printf 'sample n\n1 1.7\n5 1.45\n20 2.0\n' > "$s/n-file"

# Sample names: the whole samples.tsv, its first rows, a file without
# header or flag.
n=$out/fuzz_names
cp "$curet/samples.tsv" "$n/samples-full"
head -n 6 "$curet/samples.tsv" > "$n/samples-head"
printf '1\tFelt\n29\tPolyester (zoomed view of 2)\n' > "$n/names-noheader"
