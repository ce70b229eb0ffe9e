#!/usr/bin/env bash
# CTest: a small campaign under GNU parallel (scripts/campaign.sh). A shard that fails once is
# retried; a campaign interrupted with a shard failing for good merges what it has (exit 1), and
# run again resumes: only the failed shard runs. The merged report then grades the same as the
# campaign run unsharded (linequad diff finds nothing changed, either way).
# Usage: campaign_test.sh LINEQUAD SOURCE_DIR WORK_DIR
set -euo pipefail
linequad=$(realpath "$1") source_dir=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
# shellcheck disable=SC2054 # the commas are in the values
options=(--cases 12 --seed 9 --solvers seed,stable --families generic,near_tangent,scale --no-plots)

# A linequad that logs each shard it runs, fails shard 1 on its first try, and fails shard 2 for
# as long as $work/break_2 exists.
cat >"$work/flaky" <<EOF
#!/usr/bin/env bash
shard=""
for ((i = 1; i <= \$#; ++i)); do [ "\${!i}" = --shard ] && j=\$((i + 1)) && shard=\${!j%%/*}; done
echo "\$shard" >>"$work/calls"
if [ "\$shard" = 1 ] && [ ! -e "$work/failed_1_once" ]; then touch "$work/failed_1_once"; exit 1; fi
if [ "\$shard" = 2 ] && [ -e "$work/break_2" ]; then exit 3; fi
exec "$linequad" "\$@"
EOF
chmod +x "$work/flaky"

fail() {
  echo "FAIL: $*"
  exit 1
}
campaign() {
  LINEQUAD="$work/flaky" JOBS=2 RETRIES=1 bash "$source_dir/scripts/campaign.sh" "$work/c" 4 \
    "${options[@]}"
}

# First run: shard 1 fails once and is retried; shard 2 fails twice (its retry too).
touch "$work/break_2"
status=0
campaign >"$work/run1.log" 2>&1 || status=$?
[ "$status" = 1 ] || fail "the interrupted campaign exited $status, not 1 (shards missing)"
grep -q "shards missing: 2" "$work/run1.log" || fail "merge did not name shard 2 as missing"
[ "$(grep -c '^1$' "$work/calls")" = 2 ] || fail "shard 1 was not retried exactly once"
[ "$(grep -c '^2$' "$work/calls")" = 2 ] || fail "shard 2 was not tried twice"
missing=$(bash "$source_dir/scripts/campaign.sh" --missing "$work/c" 4)
[ "$missing" = 2 ] || fail "--missing printed '$missing', not 2"

# Resumed: only shard 2 runs.
rm "$work/break_2" "$work/calls"
campaign >"$work/run2.log" 2>&1 || fail "the resumed campaign failed: $(cat "$work/run2.log")"
[ "$(cat "$work/calls")" = 2 ] || fail "the resumed campaign ran shards $(tr '\n' ' ' <"$work/calls"), not only 2"

# Another campaign in the same directory is refused.
if LINEQUAD="$work/flaky" bash "$source_dir/scripts/campaign.sh" "$work/c" 4 --cases 13 \
  >"$work/other.log" 2>&1; then
  fail "a different campaign was run into the same directory"
fi
grep -q "holds another campaign" "$work/other.log" || fail "the refusal did not say why"

# Options a shard cannot take are refused up front, before any shard runs (--threads was accepted
# and then every shard failed).
for option in "--threads 4" "--cases-file x.jsonl" "--history h.db"; do
  # shellcheck disable=SC2086 # the option and its value, two words
  if LINEQUAD="$work/flaky" bash "$source_dir/scripts/campaign.sh" "$work/refused" 2 $option \
    >"$work/refused.log" 2>&1; then
    fail "campaign.sh accepted $option"
  fi
  grep -q "campaign.sh: " "$work/refused.log" || fail "the refusal of $option did not say why"
  [ ! -e "$work/refused/joblog" ] || fail "a shard ran with $option"
done

# A directory named to break things: a leading dash, braces (GNU parallel's replacement string),
# quotes, a command substitution. Everything lands inside it, nothing runs.
odd="-{} it's \"odd\" \$(touch PWNED)"
(cd "$work" && LINEQUAD="$linequad" JOBS=2 bash "$source_dir/scripts/campaign.sh" "$odd" 2 \
  "${options[@]}" >odd.log 2>&1) || fail "a campaign into '$odd' failed: $(cat "$work/odd.log")"
for f in shard_0/report.json shard_1/report.json merged/report.json merged/report.html; do
  [ -f "$work/$odd/$f" ] || fail "'$odd/$f' was not written"
done
[ ! -e "$work/PWNED" ] && [ ! -e PWNED ] || fail "a directory's name ran a command"
[ "$(find "$work" -maxdepth 1 -name 'shard_*' | wc -l)" = 0 ] || fail "a shard was written outside its directory"

# Two campaigns at once on one directory: the second is refused while the first runs.
printf '#!/usr/bin/env bash\nsleep 3\nexec %q "$@"\n' "$linequad" >"$work/slow"
chmod +x "$work/slow"
LINEQUAD="$work/slow" JOBS=1 bash "$source_dir/scripts/campaign.sh" "$work/busy" 2 "${options[@]}" \
  >"$work/busy1.log" 2>&1 &
first=$!
sleep 1
if LINEQUAD="$linequad" bash "$source_dir/scripts/campaign.sh" "$work/busy" 2 "${options[@]}" \
  >"$work/busy2.log" 2>&1; then
  fail "a second campaign ran in a directory while the first was running"
fi
grep -q "another campaign is running" "$work/busy2.log" || fail "the refusal did not say why: $(cat "$work/busy2.log")"
wait "$first" || fail "the first campaign failed: $(cat "$work/busy1.log")"

# The merged campaign grades as the unsharded run.
"$linequad" audit "${options[@]}" --out "$work/whole" >/dev/null 2>&1
same() {
  "$linequad" diff "$work/$1/report.json" "$work/$2/report.json" >"$work/diff.md" ||
    fail "diff $1 $2: $(cat "$work/diff.md")"
}
same whole c/merged
same c/merged whole
# The Slurm array's task script as Slurm runs it (each task with its index), then its merge job.
for k in 0 1 2 3; do
  SLURM_ARRAY_TASK_ID=$k SLURM_CPUS_PER_TASK=1 SHARDS=4 CAMPAIGN_DIR="$work/slurm" \
    AUDIT_OPTIONS="${options[*]}" LINEQUAD="$linequad" \
    bash "$source_dir/scripts/cluster/slurm-audit.sbatch" >/dev/null 2>&1 ||
    fail "the Slurm task $k failed"
done
SHARDS=4 CAMPAIGN_DIR="$work/slurm" LINEQUAD="$linequad" LINEQUAD_SOURCE="$source_dir" \
  bash "$source_dir/scripts/cluster/slurm-merge.sbatch" >/dev/null 2>&1 || fail "the Slurm merge failed"
same whole slurm/merged

# The Kubernetes Indexed Job: its shard count agrees in its three places, and each pod's command
# (the campaign's options and volume swapped for this test's) runs its own shard.
/usr/bin/python3 - "$source_dir/scripts/cluster/k8s-audit-job.yaml" "$work/k8s" "${options[*]}" \
  >"$work/pods.sh" <<'PY' || fail "k8s-audit-job.yaml: $(cat "$work/pods.sh")"
import shlex, sys, yaml
job = yaml.safe_load(open(sys.argv[1]))
spec = job["spec"]
assert job["kind"] == "Job" and spec["completionMode"] == "Indexed", "not an Indexed Job"
n = spec["completions"]
assert spec["maxFailedIndexes"] == n, "maxFailedIndexes differs from completions"
container = spec["template"]["spec"]["containers"][0]
script = container["args"][0]
assert '--shard "${JOB_COMPLETION_INDEX}/%d"' % n in script, "--shard does not say /%d" % n
assert container["command"] == ["sh", "-c"]
script = script.replace("--cases 100000 --seed 7 --threads 2", sys.argv[3] + " --threads 1")
script = script.replace("/campaign/", sys.argv[2] + "/")
for k in range(n):
    print("JOB_COMPLETION_INDEX=%d sh -c %s" % (k, shlex.quote(script)))
print("# shards %d" % n)
PY
mkdir -p "$work/bin"
ln -sf "$linequad" "$work/bin/linequad"
PATH="$work/bin:$PATH" bash -e "$work/pods.sh" >/dev/null 2>&1 || fail "a pod's command failed"
k8s_shards=$(sed -n 's/^# shards //p' "$work/pods.sh")
LINEQUAD="$linequad" bash "$source_dir/scripts/campaign.sh" --merge "$work/k8s" "$k8s_shards" \
  >/dev/null 2>&1 || fail "the merge of the Kubernetes shards failed"
[ "$(bash "$source_dir/scripts/campaign.sh" --missing "$work/k8s" "$k8s_shards")" = "" ] ||
  fail "shards missing after every pod ran"

echo "PASS: retried shard 1, resumed shard 2 alone, merged = unsharded; Slurm and Kubernetes" \
  "shards merged; an odd directory name stayed data; a second campaign at once was refused"
