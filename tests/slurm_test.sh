#!/usr/bin/env bash
# CTest: a campaign under a real Slurm (Debian's slurm-wlm and munge), started here on this one
# machine without systemd and stopped after: the project's sbatch scripts submitted as a job array
# of shards and a merge job that depends on it, as docs/audit.md says to on a cluster; the merged
# report must grade the same as the campaign run unsharded (linequad diff, both ways).
# Exits 77 (skipped, with the reason) where Slurm cannot start: not root, or not installed.
# Usage: slurm_test.sh LINEQUAD SOURCE_DIR WORK_DIR
set -euo pipefail
linequad=$(realpath "$1") source_dir=$(realpath "$2") work=$3
skip() {
  echo "SKIP: $*"
  exit 77
}
fail() {
  echo "FAIL: $*"
  for log in "$work"/*.log; do [ -f "$log" ] && { echo "--- $log"; tail -n 20 "$log"; }; done
  exit 1
}
[ "$(id -u)" = 0 ] || skip "slurmd must run as root to start jobs (run the tests as root)"
for program in munged mungekey slurmctld slurmd sbatch squeue sinfo; do
  command -v "$program" >/dev/null || skip "no $program (scripts/install-deps.sh installs slurm-wlm and munge)"
done
rm -rf "$work"
mkdir -p "$work/state" "$work/spool" "$work/campaign"
chmod 700 "$work"
work=$(realpath "$work")
host=$(hostname -s)

# munge with a key and a socket of its own, so that no system munge is needed or touched.
mungekey --create --keyfile="$work/munge.key" --force >/dev/null 2>&1 ||
  fail "mungekey could not make a key"
chmod 600 "$work/munge.key"
munged --key-file="$work/munge.key" --socket="$work/munge.socket" --pid-file="$work/munged.pid" \
  --log-file="$work/munged.log" --seed-file="$work/munge.seed" --force ||
  skip "munged would not start here: $(tail -n 3 "$work/munged.log" 2>/dev/null)"

# One node, this machine, with its cores; ports away from a system Slurm's.
cat >"$work/slurm.conf" <<CONF
ClusterName=linequadtest
SlurmctldHost=$host
SlurmctldPort=16817
SlurmdPort=16818
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$work/munge.socket
CredType=cred/munge
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MpiDefault=none
SlurmctldTimeout=30
SlurmdTimeout=30
NodeName=$host CPUs=$(nproc) RealMemory=4096 State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$work/slurm.conf"
cleanup() {
  scancel --quiet --full --user=root >/dev/null 2>&1 || true
  for pid in slurmd slurmctld munged; do
    [ -f "$work/$pid.pid" ] && kill "$(cat "$work/$pid.pid")" 2>/dev/null || true
  done
  sleep 1
  for pid in slurmd slurmctld munged; do
    [ -f "$work/$pid.pid" ] && kill -9 "$(cat "$work/$pid.pid")" 2>/dev/null || true
  done
}
trap cleanup EXIT
slurmctld -i || skip "slurmctld would not start here: $(tail -n 3 "$work/slurmctld.log" 2>/dev/null)"
slurmd || skip "slurmd would not start here: $(tail -n 3 "$work/slurmd.log" 2>/dev/null)"
for ((i = 0; i < 60; ++i)); do
  state=$(sinfo --noheader --node="$host" --format=%t 2>/dev/null || true)
  [ "$state" = idle ] && break
  sleep 1
done
[ "$state" = idle ] || skip "the Slurm node did not come up (state '$state'): $(tail -n 3 "$work/slurmd.log")"

# The campaign: 4 shards as an array, the merge after it, as docs/audit.md submits them.
options="--cases 12 --seed 9 --solvers seed,stable --families generic,near_tangent,scale --no-plots"
cd "$work"
# The variables go through the environment (--export=ALL): --export=NAME=VALUE,... would cut
# AUDIT_OPTIONS at the first comma of "--solvers seed,stable".
export CAMPAIGN_DIR="$work/campaign" SHARDS=4 AUDIT_OPTIONS="$options" LINEQUAD="$linequad"
export LINEQUAD_SOURCE="$source_dir"
jobid=$(sbatch --parsable --array=0-3 --chdir="$work" --export=ALL \
  "$source_dir/scripts/cluster/slurm-audit.sbatch") || fail "sbatch of the array failed"
merge=$(sbatch --parsable --dependency=afterany:"$jobid" --chdir="$work" --export=ALL \
  "$source_dir/scripts/cluster/slurm-merge.sbatch") || fail "sbatch of the merge failed"
for ((i = 0; i < 600; ++i)); do
  [ -z "$(squeue --noheader --jobs="$jobid,$merge" 2>/dev/null)" ] && break
  sleep 1
done
[ -z "$(squeue --noheader --jobs="$jobid,$merge" 2>/dev/null)" ] || fail "the jobs did not end in 10 minutes"
[ -f "$work/campaign/merged/report.json" ] || fail "the merge job wrote no merged report"

# shellcheck disable=SC2086 # the options are words
"$linequad" audit $options --out "$work/whole" >/dev/null 2>&1 || fail "the unsharded run failed"
"$linequad" diff "$work/whole/report.json" "$work/campaign/merged/report.json" >"$work/diff.md" ||
  fail "merged differs from unsharded: $(cat "$work/diff.md")"
"$linequad" diff "$work/campaign/merged/report.json" "$work/whole/report.json" >"$work/diff.md" ||
  fail "unsharded differs from merged: $(cat "$work/diff.md")"
echo "PASS: Slurm ran 4 shards as job array $jobid and merge job $merge after it; merged = unsharded"
