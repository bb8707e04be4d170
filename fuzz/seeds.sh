#!/bin/sh
# seeds.sh: builds the seed corpus of the fuzz targets from the real CURET
# and Cornell files (the Cornell folder sits beside CURET's), read in place
# (never copied into the repository), plus a few small hand-made inputs.
# The seeds go to OUT/<target>/, one file per seed.
#
#   fuzz/seeds.sh CURET_DIR REFERENCE_DIR OUT
set -eu

curet=$1
reference=$2
out=$3
cornell=$(dirname "$curet")/cornell-pbrt-v2

for f in "$curet/table.txt" "$curet/abrdf.dat" "$curet/samples.tsv" \
         "$reference/oren_nayar_params.tsv" "$cornell/acryl_blue.brdf" \
         "$cornell/cayman.brdf"; do
    if [ ! -r "$f" ]; then
        echo "seeds.sh: $f is missing (the seeds come from the real files)" >&2
        exit 1
    fi
done

rm -rf "$out"
mkdir -p "$out/fuzz_table" "$out/fuzz_brdf" "$out/fuzz_sample_table" \
         "$out/fuzz_names" "$out/fuzz_pbrt" "$out/fuzz_astm" "$out/fuzz_csv" \
         "$out/fuzz_merl"

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

# pbrt / Cornell .brdf: the start of a real file (LF, no description; CRLF
# with a description), records wrapping across lines, a comment after a
# number.
p=$out/fuzz_pbrt
head -n 14 "$cornell/acryl_blue.brdf" > "$p/acryl-head"
head -n 18 "$cornell/cayman.brdf" > "$p/cayman-head-crlf"
printf '# Blue paint\n\n2 # wavelengths\n450 551\n0.1 0.0 0.2\n3.0 0.25 -0.5\n' \
    > "$p/wrapped"

# ASTM: the first records of a Cornell file as a spectral export (radians,
# wavelengths in nm), an RGB export with keywords, quotes and CRLF.
a=$out/fuzz_astm
awk 'BEGIN { w = 0; n = 0 }
     { sub(/\r$/, ""); sub(/#.*/, "") }
     NF == 0 { next }
     { for (i = 1; i <= NF; i++) v[n++] = $i }
     END {
         w = v[0]; rec = 4 + w; nrec = 6
         printf "SAMPLE_NAME \"acrylic blue\"\nNUM_POINTS %d\n", nrec
         printf "VARS theta_i,phi_i,theta_s,phi_s"
         for (i = 1; i <= w; i++) printf ",%snm", v[i]
         printf "\n"
         for (r = 0; r < nrec; r++) {
             for (i = 0; i < rec; i++)
                 printf "%s%s", v[1 + w + r * rec + i], (i < rec - 1 ? "," : "\n")
         }
     }' "$cornell/acryl_blue.brdf" > "$a/spectral"
printf 'FORMAT_ID "ASTM E1392-96"\r\nSOURCE "Cornell"\r\nSAMPLE_NAME "Krylon, \\"Blue\\""\r\nNUM_POINTS 3\r\nVARS theta_i,phi_i,theta_s,phi_s,R,G,B\r\n0.872665,0,0.573513,0,0.0123,0.0456,-0.0007\r\n0.174533, 0.0 , 0.141539 ,3.141593,12.5,13.25,14\r\n1.396263,0,1.379634,-2.5,1e-3,2E-3,3.5e+0\r\n' \
    > "$a/rgb-crlf"

# tidy CSV: the first records of a Cornell file in degrees with a material
# column (two materials), one material without it, empty fields, quotes,
# comments, and a configuration list with its columns out of order.
c=$out/fuzz_csv
awk 'BEGIN { n = 0; k = 57.29577951308232 }
     { sub(/\r$/, ""); sub(/#.*/, "") }
     NF == 0 { next }
     { for (i = 1; i <= NF; i++) v[n++] = $i }
     END {
         w = v[0]; rec = 4 + w
         printf "# Cornell acryl_blue, first records\nmaterial,theta_i,phi_i,theta_o,phi_o,R,G\n"
         for (r = 0; r < 8; r++) {
             b = 1 + w + r * rec
             printf "%s,%.10g,%.10g,%.10g,%.10g,%s,%s\n", (r % 2 ? "\"acryl, blue\"" : "acryl"),
                 v[b] * k, v[b + 1] * k, v[b + 2] * k, v[b + 3] * k, v[b + 4], v[b + 30]
         }
     }' "$cornell/acryl_blue.brdf" > "$c/cornell-two-materials"
printf 'theta_i,phi_i,theta_o,phi_o,550nm,R\n10,0,20,180,0.5,\n60,-90,0,45.5,1e-3,2\n' \
    > "$c/one-material"
printf '\357\273\277note,phi_o,theta_o,phi_i,theta_i\r\nx,180,20,0,10\r\n# c\r\n,90,40,-90,30\r\n' \
    > "$c/configs-any-order"

# MERL: the header alone, the header and a few values, wrong dimensions;
# five configurations as doubles (the lookup part: 0.5 0 0.6 3, 0.2 1 0.3
# -2, 1.2 0 1.1 3.14159, the normal pair, a grazing mirror pair).
m=$out/fuzz_merl
printf '\132\000\000\000\132\000\000\000\264\000\000\000' > "$m/header"
{ printf '\132\000\000\000\132\000\000\000\264\000\000\000'; head -c 256 "$cornell/cayman.brdf"; } > "$m/header-and-text"
printf '\132\000\000\000\132\000\000\000\150\001\000\000' > "$m/dims-90-90-360"
printf '\000\000\000\000\000\000\340\077\000\000\000\000\000\000\000\000\063\063\063\063\063\063\343\077\000\000\000\000\000\000\010\100\232\231\231\231\231\231\311\077\000\000\000\000\000\000\360\077\063\063\063\063\063\063\323\077\000\000\000\000\000\000\000\300\063\063\063\063\063\063\363\077\000\000\000\000\000\000\000\000\232\231\231\231\231\231\361\077\156\206\033\360\371\041\011\100\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\030\055\104\124\373\041\371\077\063\063\063\063\063\063\323\077\030\055\104\124\373\041\371\077\260\076\171\263\141\210\013\100' \
    > "$m/configs"
