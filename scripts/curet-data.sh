#!/bin/sh
# curet-data.sh: finds CURET's table.txt and abrdf.dat for the main job and
# prints the folder that holds them (only that, on stdout).
#
#   scripts/curet-data.sh [DIR]
#
# DIR, when it holds both files, is used as it is. Otherwise the files come
# from the per-user cache ${XDG_CACHE_HOME:-$HOME/.cache}/brdffit/curet,
# downloaded there when missing from $BRDFFIT_CURET_URL (default: CURET's
# published location; http://, https:// and file:// URLs) and used only
# when their SHA-256 sums match data/curet.sha256. Without a network it
# says which files to download, from where, and where to put them.
# Exit status: 0 with the folder printed; 1 otherwise (nothing printed).
set -eu

CURET_PAGE="https://www.cs.columbia.edu/CAVE/software/curet/html/brdfm.html"
CURET_URL="https://www.cs.columbia.edu/CAVE/software/curet/data"
FILES="table.txt abrdf.dat"

here=$(cd "$(dirname "$0")/.." && pwd)
sums="$here/data/curet.sha256"
dir=${1:-}
url=${BRDFFIT_CURET_URL:-$CURET_URL}
url=${url%/}
cache="${XDG_CACHE_HOME:-${HOME:?}/.cache}/brdffit/curet"

say() { echo "curet-data: $*" >&2; }

if [ -n "$dir" ] && [ -f "$dir/table.txt" ] && [ -f "$dir/abrdf.dat" ]; then
    echo "$dir"
    exit 0
fi

# The expected sum of file $1 (data/curet.sha256), and the one of path $2.
expected() { awk -v f="$1" '$2 == f { print $1 }' "$sums"; }
actual() { sha256sum "$1" | cut -d ' ' -f 1; }

offline() {
    say "the CURET data are not here and could not be downloaded."
    echo "Download these two files (about 110 KB; CURET, Columbia University," >&2
    echo "listed on $CURET_PAGE):" >&2
    for f in $FILES; do
        echo "    $CURET_URL/$f" >&2
    done
    echo "and put them in" >&2
    echo "    $cache/" >&2
    echo "or run: make run CURET=DIR  (a folder holding table.txt and abrdf.dat)." >&2
    echo "Their SHA-256 sums are in $sums." >&2
    exit 1
}

# Downloads $1 into $2: file:// by copying, else curl or wget.
fetch() {
    case $1 in
    file://*) cp -- "${1#file://}" "$2" 2>/dev/null ;;
    *)
        if command -v curl >/dev/null 2>&1; then
            curl -fsSL --max-time 60 -o "$2" "$1" 2>/dev/null
        elif command -v wget >/dev/null 2>&1; then
            wget -q -T 60 -O "$2" "$1"
        else
            say "neither curl nor wget is installed"
            return 1
        fi
        ;;
    esac
}

if [ -n "$dir" ] && [ "$dir" != "$cache" ]; then
    say "$dir does not hold table.txt and abrdf.dat; using $cache"
fi
mkdir -p "$cache" || { say "cannot create $cache"; exit 1; }
for f in $FILES; do
    want=$(expected "$f")
    [ -n "$want" ] || { say "$sums has no sum for $f"; exit 1; }
    if [ -f "$cache/$f" ] && [ "$(actual "$cache/$f")" = "$want" ]; then
        continue
    fi
    part="$cache/.$f.part"
    rm -f "$part"
    say "downloading $url/$f"
    if ! fetch "$url/$f" "$part" || [ ! -s "$part" ]; then
        rm -f "$part"
        say "cannot download $url/$f"
        offline
    fi
    got=$(actual "$part")
    if [ "$got" != "$want" ]; then
        rm -f "$part" "$cache/$f"
        say "$url/$f is not CURET's $f: its SHA-256 is $got, $sums expects $want; refused"
        exit 1
    fi
    mv -f "$part" "$cache/$f"
done
echo "$cache"
