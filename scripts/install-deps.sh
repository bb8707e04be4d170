#!/bin/sh
# install-deps.sh: installs the Debian packages brdffit needs, only those
# that are missing (idempotent). Runs apt-get as root, or through sudo.
#
#   scripts/install-deps.sh          build + test dependencies
#   scripts/install-deps.sh bench    also the benchmark's numpy baseline and
#                                    the numpy/scipy peers (make bench,
#                                    make bench-glossy)
#   scripts/install-deps.sh fuzz     also clang and libFuzzer (make fuzz)
#   scripts/install-deps.sh valgrind also valgrind (make valgrind)
#   scripts/install-deps.sh coverage also gcovr (make coverage)
#   scripts/install-deps.sh format   also clang-format and git clang-format
#                                    (make format)
set -eu

# libplplot-dev, plplot-driver-cairo, fonts-dejavu-core: the report's
# figures (PNG, SVG, PDF through PLplot's cairo drivers, and a font);
# zlib1g-dev: the report's PNG writer; nettle-dev: the SHA-256 sums of
# the report's inputs; python3-html5lib: the test that
# parses report.html; curl: `make run` fetches the CURET files when they
# are not on the machine (scripts/curet-data.sh).
# python3-numpy, python3-cffi, python3-pytest: the Python package (python/)
# and its tests; python3-pandas: the test of Records.to_dataframe (the
# package itself never needs pandas); python3-pip: `pip install ./python`.
PACKAGES="pkg-config libgsl-dev libcriterion-dev libplplot-dev \
plplot-driver-cairo fonts-dejavu-core zlib1g-dev nettle-dev python3-html5lib curl \
python3-numpy python3-cffi python3-pytest python3-pandas python3-pip"
for group in "$@"; do
    case $group in
    # bench/numpy_baseline.py; ../shared/peers/rank_baseline.py and
    # glossy_peer.py (scipy)
    bench) PACKAGES="$PACKAGES python3-numpy python3-scipy" ;;
    fuzz) PACKAGES="$PACKAGES clang libclang-rt-14-dev" ;;
    valgrind) PACKAGES="$PACKAGES valgrind" ;;
    coverage) PACKAGES="$PACKAGES gcovr" ;;
    format) PACKAGES="$PACKAGES clang-format" ;;
    *) echo "install-deps: unknown group '$group' (bench, fuzz, valgrind," \
            "coverage, format)" >&2
       exit 2 ;;
    esac
done

missing=""
for p in $PACKAGES; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed"; then
        missing="$missing $p"
    fi
done
[ -z "$missing" ] && exit 0

echo "install-deps: installing:$missing" >&2
if [ "$(id -u)" -eq 0 ]; then
    SUDO=""
elif command -v sudo >/dev/null 2>&1; then
    SUDO="sudo"
else
    echo "install-deps: need root (or sudo) to install:$missing" >&2
    exit 1
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
# shellcheck disable=SC2086
$SUDO apt-get install -y -qq --no-install-recommends $missing >/dev/null
