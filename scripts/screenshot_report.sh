#!/bin/sh
# Headless screenshot of the validation report, to look at the page as a
# browser renders it (tables, figure placement, SVG sizes).
#
#   scripts/screenshot_report.sh [report.html] [out.png] [width] [height]
#
# Defaults: reports/report.html, /tmp/report.png, 1280 x 4000 pixels (the top
# of the page; pass a larger height for more). Needs Chromium, which is not
# part of `make setup`: `apt-get install -y chromium` (as root) installs it.
# Without Chromium the script says so and exits 0.
set -eu
html=${1:-reports/report.html}
png=${2:-/tmp/report.png}
width=${3:-1280}
height=${4:-4000}
browser=""
for b in chromium chromium-browser google-chrome; do
  if command -v "$b" >/dev/null 2>&1; then browser=$b; break; fi
done
if [ -z "$browser" ]; then
  echo "screenshot_report: no chromium found (apt-get install -y chromium); nothing done"
  exit 0
fi
if [ ! -f "$html" ]; then
  echo "screenshot_report: $html not found (make validate writes it)" >&2
  exit 1
fi
abs=$(cd "$(dirname "$html")" && pwd)/$(basename "$html")
# --no-sandbox: needed when running as root (containers).
"$browser" --headless --no-sandbox --disable-gpu --hide-scrollbars \
  --screenshot="$png" --window-size="$width,$height" "file://$abs" 2>/dev/null
echo "screenshot_report: $png ($width x $height) of $abs"
