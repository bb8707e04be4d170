#!/bin/sh
# test_install.sh BUILD CC CMAKE: installs the built brdffit into a temporary
# prefix, moves that prefix elsewhere (both brdffit.pc and the CMake package
# must follow), and builds tests/install/consumer.c against it three ways --
# pkg-config (shared), pkg-config --static (linking libbrdffit.a, so every
# private dependency must be listed) and CMake's find_package
# (brdffit::brdffit and brdffit::brdffit_static) -- running each program.
# Registered with CTest in the plain build (tests/CMakeLists.txt).
set -eu
build=$1
cc=$2
cmake=$3
here=$(cd "$(dirname "$0")" && pwd)
tmp=$(mktemp -d "${TMPDIR:-/tmp}/brdffit-install.XXXXXX")
trap 'rm -rf "$tmp"' EXIT INT TERM
cflags="-std=c11 -Wall -Wextra -Wpedantic -Werror -D_XOPEN_SOURCE=700"

fail() {
    echo "test_install: FAILED: $*" >&2
    exit 1
}
# needs EXE LIB: whether the dynamic section of EXE names LIB.
needs() {
    readelf -d "$1" | grep -q "NEEDED.*\[$2"
}

"$cmake" --install "$build" --prefix "$tmp/staged" >/dev/null
mv "$tmp/staged" "$tmp/prefix" # relocated: nothing may point at staged/
prefix=$tmp/prefix
pc=$(find "$prefix" -name brdffit.pc)
[ -n "$pc" ] || fail "no brdffit.pc installed"
libdir=$(dirname "$(dirname "$pc")")
grep -rq "$tmp/staged" "$prefix" && fail "an installed file names the staging prefix"

echo "== pkg-config, shared ($pc)"
export PKG_CONFIG_PATH="$libdir/pkgconfig"
[ "$(pkg-config --modversion brdffit)" = "$("$build/brdffit" --version | awk '{print $NF}')" ] ||
    fail "pkg-config --modversion differs from brdffit --version"
[ "$(cd "$(pkg-config --variable=prefix brdffit)" && pwd -P)" = "$(cd "$prefix" && pwd -P)" ] ||
    fail "pkg-config's prefix is not the relocated prefix"
# shellcheck disable=SC2046
"$cc" $cflags -o "$tmp/pc_shared" "$here/consumer.c" \
    $(pkg-config --cflags --libs brdffit gsl) -lm
needs "$tmp/pc_shared" libbrdffit.so || fail "pc_shared does not load libbrdffit.so"
LD_LIBRARY_PATH="$libdir" "$tmp/pc_shared"

echo "== pkg-config --static"
# -l:libbrdffit.a: the static library although the shared one is beside it
# (README "Installing and using it from another project").
# shellcheck disable=SC2046
"$cc" $cflags -o "$tmp/pc_static" "$here/consumer.c" \
    $(pkg-config --static --cflags --libs brdffit gsl | sed 's/-lbrdffit/-l:libbrdffit.a/')
needs "$tmp/pc_static" libbrdffit.so && fail "pc_static loads libbrdffit.so"
"$tmp/pc_static"
unset PKG_CONFIG_PATH

echo "== find_package(brdffit)"
"$cmake" -S "$here/consumer" -B "$tmp/cmake" -DCMAKE_C_COMPILER="$cc" \
    -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_C_FLAGS="$cflags" >/dev/null
"$cmake" --build "$tmp/cmake" >/dev/null
needs "$tmp/cmake/consumer_shared" libbrdffit.so ||
    fail "consumer_shared does not load libbrdffit.so"
needs "$tmp/cmake/consumer_static" libbrdffit.so &&
    fail "consumer_static loads libbrdffit.so"
"$tmp/cmake/consumer_shared"
"$tmp/cmake/consumer_static"
echo "test_install: all three consumers built and passed"
