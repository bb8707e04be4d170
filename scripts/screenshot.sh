#!/bin/sh
# screenshot.sh: opens report.html in headless Chromium (Debian package
# chromium, installed here if missing -- never by the tests), checks that
# every image of the page loaded, and saves a screenshot of the top.
#
#   scripts/screenshot.sh out/report.html out/report-screenshot.png
#
# The page sets data-images-ok="yes" on <body> once every image has loaded
# (an inline script; no network); this reads it from the DOM Chromium dumps.
set -eu

page=${1:?usage: screenshot.sh REPORT.html SHOT.png}
shot=${2:?usage: screenshot.sh REPORT.html SHOT.png}
[ -f "$page" ] || { echo "screenshot: $page not found (run make run)" >&2; exit 1; }

if ! command -v chromium >/dev/null 2>&1; then
    echo "screenshot: installing chromium" >&2
    SUDO=""
    [ "$(id -u)" -eq 0 ] || SUDO="sudo"
    export DEBIAN_FRONTEND=noninteractive
    $SUDO apt-get update -qq
    $SUDO apt-get install -y -qq --no-install-recommends chromium >/dev/null
fi

url="file://$(cd "$(dirname "$page")" && pwd)/$(basename "$page")"
profile=$(mktemp -d)
dom=$(mktemp)
trap 'rm -rf "$profile" "$dom"' EXIT
flags="--headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
--disable-background-networking --disable-component-update --disable-sync \
--user-data-dir=$profile --virtual-time-budget=20000"

# shellcheck disable=SC2086
chromium $flags --dump-dom "$url" >"$dom" 2>/dev/null
loaded=$(sed -n 's/.*data-images="\([0-9]*\/[0-9]*\)".*/\1/p' "$dom" | head -n 1)
# shellcheck disable=SC2086
chromium $flags --window-size=1280,2400 --screenshot="$shot" "$url" \
    >/dev/null 2>&1
if ! grep -q 'data-images-ok="yes"' "$dom"; then
    echo "screenshot: not every image of $page loaded (${loaded:-none} loaded)" >&2
    exit 1
fi
echo "screenshot: all images loaded ($loaded); screenshot in $shot"
