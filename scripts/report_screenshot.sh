#!/usr/bin/env bash
# The report's first screen as a reader sees it: headless Chromium at 1,400 px wide on
# reports/latest/report.html (or REPORT), into docs/images/report_first_screen.png (1,400 x 1,000)
# and docs/images/verdict.png (the verdict's solver table alone, for the README).
set -euo pipefail
cd "$(dirname "$0")/.."
report="${REPORT:-reports/latest/report.html}"
profile=$(mktemp -d)
trap 'rm -rf "$profile"' EXIT
shot() { # WIDTH HEIGHT OUT
  chromium --headless --no-sandbox --disable-gpu --disable-background-networking \
    --disable-component-update --no-first-run --no-default-browser-check \
    --host-resolver-rules="MAP * ~NOTFOUND" --user-data-dir="$profile" --hide-scrollbars \
    --window-size="$1,$2" --screenshot="$3" "file://$PWD/$report" >/dev/null 2>&1
}
shot 1400 1000 docs/images/report_first_screen.png
shot 1100 400 docs/images/verdict.png
echo "docs/images/report_first_screen.png, docs/images/verdict.png from $report"
