#!/usr/bin/env bash
# CTest: a small audit writes report.html; headless Chromium (no sandbox, no network: every host
# name resolves to nothing, background networking off) opens it beside html_report_check.html,
# which checks that the verdict comes first and fits the first screen, its tables render and sort,
# its figures decode, its copy buttons answer and that it loads nothing from outside the file;
# and that the page is at most 1.5 MiB. Fails on any console message (the report logs
# nothing; a script error or a blocked load shows up there).
# Usage: html_report_test.sh LINEQUAD CHROMIUM SOURCE_DIR WORK_DIR
set -euo pipefail
linequad=$1 chromium=$2 source_dir=$3 work=$4
rm -rf "$work"
mkdir -p "$work"
# The default audit's solvers and families (what its first screen must hold), few cases: a
# report's layout and size do not grow with its cases.
"$linequad" audit --cases 10 --seed 7 --out "$work/report" >/dev/null 2>"$work/audit.log"
cp "$source_dir/html_report_check.html" "$work/report/check.html"
size=$(stat -c %s "$work/report/report.html")
echo "report.html: $size bytes"
if [ "$size" -gt 1572864 ]; then
  echo "report.html is $size bytes, more than 1.5 MiB"
  exit 1
fi

status=0
timeout 120 "$chromium" --headless --no-sandbox --disable-gpu --disable-background-networking \
  --disable-component-update --no-first-run --no-default-browser-check \
  --host-resolver-rules="MAP * ~NOTFOUND" --allow-file-access-from-files \
  --user-data-dir="$work/profile" --window-size=1400,1100 --virtual-time-budget=10000 \
  --enable-logging=stderr --v=0 --dump-dom "file://$work/report/check.html" \
  >"$work/dom.html" 2>"$work/chromium.log" || status=$?
if [ "$status" != 0 ]; then
  echo "chromium exited with $status:"
  tail -20 "$work/chromium.log"
  exit 1
fi

verdict=$(sed -n '/<pre id="verdict">/,/<\/pre>/p' "$work/dom.html" | sed 's/<[^>]*>//g')
echo "$verdict"
console=$(grep -E ':CONSOLE[:(]' "$work/chromium.log" || true)
if [ -n "$console" ]; then
  echo "the console was not silent:"
  echo "$console"
  exit 1
fi
case "$verdict" in
PASS*) exit 0 ;;
*) exit 1 ;;
esac
