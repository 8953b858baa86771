#!/usr/bin/env bash
# The Slurm round trip of `fireswarm sweep`, for real: starts a single-node Slurm
# (munged, slurmctld, slurmd from Debian's slurm-wlm, as root, its state in a
# temporary directory and on ports of its own), emits a small sweep's job-array
# script, submits it with `sbatch --wait`, collects, and compares the summary
# byte for byte with the same sweep run locally. Stops every daemon it started.
# Exits 77 (ctest's SKIP_RETURN_CODE) with the reason where it cannot run: not
# root, the packages missing, or the daemons not coming up.
#   slurm_sweep_test.sh FIRESWARM_BIN
set -euo pipefail

readonly kSkip=77
readonly kReadyDeadlineS=60
bin=$(readlink -f "$1")

skip() {
  echo "SKIP: $*" >&2
  exit "$kSkip"
}

[ "$(id -u)" -eq 0 ] || skip "needs root to start munged, slurmctld and slurmd"
for tool in munged munge unmunge slurmctld slurmd sbatch sinfo squeue scancel setpriv; do
  command -v "$tool" >/dev/null 2>&1 ||
    skip "$tool not found: install Debian's slurmctld slurmd slurm-client munge (scripts/install-deps.sh)"
done
[ -r /etc/munge/munge.key ] || skip "/etc/munge/munge.key missing (the munge package makes it)"

work=$(mktemp -d /tmp/fireswarm_slurm.XXXXXX)
chmod 755 "$work"
pids=()
ctld_started=0
cleanup() {
  local status=$?
  # Jobs first (a job's processes outlive slurmd under proctrack/linuxproc).
  if [ "$ctld_started" -eq 1 ]; then
    scancel --quiet --user=root 2>/dev/null || true
    for _ in $(seq 1 100); do
      [ -z "$(squeue -h 2>/dev/null || true)" ] && break
      sleep 0.1
    done
  fi
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do wait "$pid" 2>/dev/null || true; done
  if [ "$status" -ne 0 ] && [ "$status" -ne "$kSkip" ]; then
    for log in "$work"/*.log; do
      [ -f "$log" ] && { echo "== $log"; tail -n 30 "$log"; }
    done
  fi
  rm -rf "$work"
  exit "$status"
}
trap cleanup EXIT

# munge: a munged of our own on its own socket (a system one is left alone).
export MUNGE_SOCKET="$work/munge/munge.socket"
mkdir -p "$work/munge"
chown munge:munge "$work/munge"
setpriv --reuid=munge --regid=munge --init-groups munged --socket="$MUNGE_SOCKET" --pid-file="$work/munge/munged.pid" \
  --log-file="$work/munge.log" --seed-file="$work/munge/seed" --foreground >"$work/munged.log" 2>&1 &
pids+=($!)
ready=0
for _ in $(seq 1 $((kReadyDeadlineS * 10))); do
  if munge -S "$MUNGE_SOCKET" -n 2>/dev/null | unmunge -S "$MUNGE_SOCKET" >/dev/null 2>&1; then
    ready=1
    break
  fi
  sleep 0.1
done
[ "$ready" -eq 1 ] || skip "munged did not come up (see $work/munge.log)"

# Ports of our own, so a real Slurm on this machine is left alone.
ctld_port=$((20000 + RANDOM % 20000))
node_port=$((ctld_port + 1))
cpus=$(nproc)
mkdir -p "$work/state" "$work/spool"
cat >"$work/slurm.conf" <<EOF
ClusterName=fireswarm-test
SlurmctldHost=localhost
SlurmctldPort=$ctld_port
SlurmdPort=$node_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$MUNGE_SOCKET
CredType=cred/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
NodeName=localhost NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=test Nodes=localhost Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF="$work/slurm.conf"
slurmctld -D -i -f "$SLURM_CONF" >"$work/slurmctld.out" 2>&1 &
pids+=($!)
ctld_started=1
slurmd -D -N localhost -f "$SLURM_CONF" >"$work/slurmd.out" 2>&1 &
pids+=($!)
ready=0
for _ in $(seq 1 $((kReadyDeadlineS * 10))); do
  state=$(sinfo -h -n localhost -o %t 2>/dev/null || true)
  if [ "$state" = "idle" ]; then
    ready=1
    break
  fi
  sleep 0.1
done
[ "$ready" -eq 1 ] || skip "the Slurm node did not become idle (state '${state:-none}'; see $work/slurmctld.log)"

# A small sweep of a tiny scenario: 2 fleet sizes x 2 seeds in 2 array tasks.
cat >"$work/tiny.yaml" <<'EOF'
name: tiny
seed: 7
duration_s: 60
area:
  polygon: [[7.0, 45.0], [7.010146, 45.0], [7.010146, 45.0045], [7.0, 45.0045]]
fleet:
  count: 2
  launch: {lat: 44.9995, lon: 7.005}
fires:
  - {lat: 45.00230, lon: 7.00480}
EOF
cat >"$work/sweep.yaml" <<'EOF'
name: slurm_round_trip
scenario: tiny.yaml
seeds: {first: 1, count: 2}
axes:
  fleet.count: [1, 2]
EOF
chmod -R a+rX "$work"

"$bin" sweep "$work/sweep.yaml" --out "$work/local" --jobs 2 >"$work/local.log" 2>&1
"$bin" sweep "$work/sweep.yaml" --out "$work/slurm" --emit slurm --chunks 2
grep -q -- '--array=0-1' "$work/slurm/sweep.sbatch"
timeout 300 sbatch --wait --quiet "$work/slurm/sweep.sbatch"
[ ! -e "$work/slurm/summary.json" ] || { echo "FAIL: an array task wrote the summary"; exit 1; }
ls "$work"/slurm/slurm/*.out >/dev/null  # each task's Slurm output file
"$bin" sweep --collect "$work/slurm"
for file in summary.json summary.csv summary.html; do
  if ! cmp "$work/local/$file" "$work/slurm/$file"; then
    echo "FAIL: $file differs between --jobs 2 and Slurm"
    diff "$work/local/$file" "$work/slurm/$file" | head -20
    exit 1
  fi
done
echo "slurm_sweep: 4 runs through sbatch --array=0-1; summary identical to --jobs 2"
