#!/bin/sh
# Open an mbxval HTML report in a real headless browser (Debian's chromium package) and check that
# it loads and that every plot (inline SVG, or a PNG in older reports) is laid out; leave a screenshot
# (screenshot.png) next to the report.
#
# Usage: scripts/check_report_in_browser.sh [REPORT_DIR]
#   REPORT_DIR defaults to ./mbxval-report; when it has no index.html, a small report is rendered
#   there first (`mbxval run` on the slider-crank). Set MBXVAL to the command to use (default
#   `mbxval`, e.g. MBXVAL=.venv/bin/mbxval). Installs chromium with apt-get when it is missing
#   (needs root). Exit status 0 when every plot loaded, 1 otherwise.
set -eu

dir=${1:-mbxval-report}
mbxval=${MBXVAL:-mbxval}
browser=/usr/bin/chromium

if [ ! -x "$browser" ]; then
    echo "chromium is missing: installing Debian's package" >&2
    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >/dev/null
fi
if [ ! -f "$dir/index.html" ]; then
    $mbxval run --out "$dir" --scenario slider_crank --quiet
fi

url="file://$(cd "$dir" && pwd)/index.html"
flags="--headless --no-sandbox --disable-gpu --hide-scrollbars"
# The page's own script sets data-plots-loaded="decoded/total" on <body> once it has loaded.
loaded=$($browser $flags --dump-dom "$url" 2>/dev/null | grep -o 'data-plots-loaded="[0-9]*/[0-9]*"' || true)
$browser $flags --window-size=1280,3000 --screenshot="$dir/screenshot.png" "$url" >/dev/null 2>&1

counts=$(echo "$loaded" | tr -dc '0-9/')
good=${counts%/*}
total=${counts#*/}
if [ -z "$loaded" ] || [ "$total" -eq 0 ] || [ "$good" -ne "$total" ]; then
    echo "FAIL: $url: plots loaded ${counts:-none} (screenshot: $dir/screenshot.png)" >&2
    exit 1
fi
echo "ok: $url loaded in $($browser --version), $good/$total plots decoded; screenshot: $dir/screenshot.png"
