#!/usr/bin/env bash
# A campaign of N shards under GNU parallel, then merged:
#
#   scripts/campaign.sh DIR N [linequad audit options...]
#
# Each shard K runs `linequad audit OPTIONS --shard K/N --out DIR/shard_K`; GNU parallel keeps
# DIR/joblog, retries a failed shard (RETRIES, default 1), and on a second call with the same DIR
# runs only the shards that have not succeeded yet (--resume-failed): an interrupted campaign
# resumes where it stopped. Then `linequad merge --out DIR/merged` combines the shards there are;
# it exits 1, naming them, while shards are missing.
#
#   scripts/campaign.sh --missing DIR N   prints the shards without a complete report (for a
#                                          Slurm array or a Kubernetes Job to run again)
#   scripts/campaign.sh --merge DIR N     merges the shards' reports there are into DIR/merged
#                                          (what the Slurm and Kubernetes merge jobs run)
#
# Environment: LINEQUAD (the program; default build/compare/linequad), JOBS (shards at a time;
# default: one per core, each shard on one thread), RETRIES, HISTORY (a database that merge
# appends the merged report to), COMMIT (the commit to record it under).
#
# DIR may be any name (spaces, quotes, a leading dash, braces): it reaches every command as one
# argument, and GNU parallel's command holds none of it (the shard runs this script again, which
# reads DIR from the environment and the audit's options from DIR/campaign). One campaign runs
# in a DIR at a time (DIR/.campaign.lock).
set -euo pipefail
self="$(cd "$(dirname "$0")" && pwd)/$(basename "$0")"
root="$(cd "$(dirname "$0")/.." && pwd)"
linequad="${LINEQUAD:-$root/build/compare/linequad}"

# A path that no command reads as an option.
safe_path() {
  case "$1" in
  -*) printf './%s' "$1" ;;
  *) printf '%s' "$1" ;;
  esac
}

# One shard, as GNU parallel runs it: the campaign's options read back from DIR/campaign (NUL
# separated, as written), DIR from the environment.
if [ "${1:-}" = --run-shard ]; then
  dir=$LINEQUAD_CAMPAIGN_DIR k=$2 n=$3
  mapfile -d '' options <"$dir/campaign"
  exec "$linequad" audit "${options[@]:1}" --threads 1 --shard "$k/$n" --out "$dir/shard_$k"
fi

usage() {
  sed -n '2,20p' "$0" | sed 's/^# \{0,1\}//' >&2
  exit 2
}

# The shards of DIR whose report is there and complete.
complete_shard() {
  local report="$1/shard_$2/report.json"
  [ -f "$report" ] && grep -q '"status": *"complete"' -- "$report"
}

# DIR/merged from the shard reports there are; exits 1 while some are missing or incomplete.
merge_shards() {
  local dir=$1 n=$2 k
  local reports=() history=()
  for ((k = 0; k < n; ++k)); do
    [ -f "$dir/shard_$k/report.json" ] && reports+=("$dir/shard_$k/report.json")
  done
  if [ ${#reports[@]} = 0 ]; then
    echo "campaign.sh: no shard wrote a report in $dir" >&2
    return 1
  fi
  [ -z "${HISTORY:-}" ] || history+=(--history "$HISTORY")
  [ -z "${COMMIT:-}" ] || history+=(--commit "$COMMIT")
  "$linequad" merge --out "$dir/merged" "${history[@]}" "${reports[@]}"
}

if [ "${1:-}" = --merge ]; then
  [ $# = 3 ] || usage
  merge_shards "$(safe_path "$2")" "$3"
  exit
fi

if [ "${1:-}" = --missing ]; then
  [ $# = 3 ] || usage
  dir=$(safe_path "$2") n=$3
  missing=()
  for ((k = 0; k < n; ++k)); do
    complete_shard "$dir" "$k" || missing+=("$k")
  done
  (IFS=,; echo "${missing[*]}")
  exit 0
fi

[ $# -ge 2 ] || usage
dir=$(safe_path "$1") n=$2
shift 2
case "$n" in
'' | *[!0-9]* | 0) echo "campaign.sh: N must be a whole number of shards >= 1, not '$n'" >&2; exit 2 ;;
esac
# What a shard cannot take is refused here, before any shard runs (each would fail alone).
for a in "$@"; do
  case "$a" in
  --shard | --shard=* | --out | --out=*)
    echo "campaign.sh: the campaign sets $a itself" >&2
    exit 2
    ;;
  --threads | --threads=*)
    echo "campaign.sh: each shard runs on one thread (--threads 1); JOBS sets how many shards run at a time" >&2
    exit 2
    ;;
  --cases-file | --cases-file=* | --results | --results=*)
    echo "campaign.sh: $a grades a file, not a campaign of shards" >&2
    exit 2
    ;;
  --history | --history=* | --commit | --commit=*)
    echo "campaign.sh: the merge records the campaign's history (HISTORY=DB COMMIT=ID), not $a in each shard" >&2
    exit 2
    ;;
  esac
done
command -v parallel >/dev/null || { echo "campaign.sh: GNU parallel not found (scripts/install-deps.sh installs it)" >&2; exit 2; }
[ -x "$linequad" ] || { echo "campaign.sh: $linequad is not a program (LINEQUAD=...)" >&2; exit 2; }

mkdir -p -- "$dir"
# One campaign at a time in a directory: a second one started on it is refused.
exec 9>>"$dir/.campaign.lock"
if ! flock -n 9; then
  echo "campaign.sh: another campaign is running in $dir ($dir/.campaign.lock is held)" >&2
  exit 2
fi
# One campaign per directory: its shards must belong together. Its options, NUL separated (any
# text survives), are what each shard runs.
printf '%s\0' "shards $n" "$@" >"$dir/campaign.new"
if [ -f "$dir/campaign" ] && ! cmp -s "$dir/campaign" "$dir/campaign.new"; then
  echo "campaign.sh: $dir holds another campaign:" >&2
  diff <(tr '\0' '\n' <"$dir/campaign") <(tr '\0' '\n' <"$dir/campaign.new") >&2 || true
  rm -f "$dir/campaign.new"
  exit 2
fi
mv "$dir/campaign.new" "$dir/campaign"

status=0
export LINEQUAD_CAMPAIGN_DIR="$dir" LINEQUAD="$linequad"
seq 0 $((n - 1)) | parallel -q --jobs "${JOBS:-$(nproc)}" --joblog "$dir/joblog" --resume-failed \
  --retries "$((${RETRIES:-1} + 1))" --halt never \
  bash "$self" --run-shard "{}" "$n" \
  >>"$dir/shards.log" 2>&1 || status=$?
[ "$status" = 0 ] || echo "campaign.sh: $status shard(s) failed (see $dir/joblog and $dir/shards.log)" >&2

merge_shards "$dir" "$n"
