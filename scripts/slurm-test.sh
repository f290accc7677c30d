#!/usr/bin/env bash
# Renders the reference batch job (jobs/default_turntable.ron) on a real Slurm: Debian's
# slurm-wlm and munge, started here as a one-node cluster (slurmctld + slurmd, state in a
# temporary folder), the job submitted as a 2-task array with deploy/slurm/render.sbatch and
# waited for; then the shards are merged and every output is compared byte for byte with a
# local, unsharded run. Skips (exit 0, with the reason) only where Slurm cannot be installed.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD

SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
if ! command -v slurmctld >/dev/null 2>&1 || ! command -v munged >/dev/null 2>&1; then
    echo "slurm-test: installing slurm-wlm and munge (Debian)" >&2
    if ! { $SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq \
        --no-install-recommends slurm-wlm munge >/dev/null; }; then
        echo "slurm-test: SKIPPED: slurm-wlm and munge cannot be installed on this machine" >&2
        exit 0
    fi
fi
[ -x target/release/hatchery ] || cargo build --release --bin hatchery

work=$(mktemp -d /tmp/hatchery-slurm.XXXXXX)
host=$(hostname -s)
conf=$work/slurm.conf
cleanup() {
    SLURM_CONF=$conf scontrol shutdown >/dev/null 2>&1 || true
    sleep 1
    for pid in "$work"/slurmctld.pid "$work"/slurmd.pid "$work"/munged.pid; do
        [ -f "$pid" ] && kill "$(cat "$pid")" 2>/dev/null || true
    done
    rm -rf "$work"
}
trap cleanup EXIT

# munge: its own key, socket and state in $work (not the machine's).
mkdir -p "$work/munge" "$work/spool" "$work/state"
chmod 700 "$work/munge"
mungekey --create --keyfile "$work/munge/munge.key" 2>/dev/null || \
    dd if=/dev/urandom of="$work/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$work/munge/munge.key"
munged --force --key-file "$work/munge/munge.key" --socket "$work/munge/socket" \
    --pid-file "$work/munged.pid" --log-file "$work/munge/log" --seed-file "$work/munge/seed"

cpus=$(nproc)
user=$(id -un)
cat > "$conf" <<CONF
ClusterName=hatchery-test
SlurmctldHost=$host(127.0.0.1)
SlurmUser=$user
SlurmdUser=$user
AuthType=auth/munge
AuthInfo=socket=$work/munge/socket
CredType=cred/munge
MpiDefault=none
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
SlurmctldPort=16817
SlurmdPort=16818
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmdSpoolDir=$work/spool
StateSaveLocation=$work/state
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$conf
slurmctld -f "$conf"
slurmd -f "$conf"
for _ in $(seq 60); do
    state=$(sinfo -h -o %t 2>/dev/null || true)
    [[ "$state" == idle* ]] && break
    sleep 1
done
if [[ "$state" != idle* ]]; then
    echo "slurm-test: the one-node cluster did not come up (node state: '${state:-none}')" >&2
    tail -5 "$work/slurmctld.log" "$work/slurmd.log" >&2 || true
    exit 1
fi
echo "slurm-test: one-node cluster up ($host, $cpus CPUs, Slurm $(sinfo -V | cut -d' ' -f2))"

out=$work/out
job=$root/jobs/default_turntable.ron
HATCHERY=$root/target/release/hatchery sbatch --wait --array=0-1 --chdir="$work" \
    --output="$work/task-%a.log" deploy/slurm/render.sbatch "$job" "$out" >/dev/null
for t in 0 1; do
    grep -q "rendered" "$work/task-$t.log" || { echo "slurm-test: task $t did not render" >&2; cat "$work/task-$t.log" >&2; exit 1; }
done
target/release/hatchery batch "$job" --out "$out" --merge
target/release/hatchery batch "$job" --out "$work/local" >/dev/null 2>&1
n=0
for f in "$work/local"/*.png; do
    cmp -s "$f" "$out/$(basename "$f")" || { echo "slurm-test: $(basename "$f") differs from the local run" >&2; exit 1; }
    n=$((n + 1))
done
[ -f "$out/manifest-0-of-2.json" ] && [ -f "$out/manifest-1-of-2.json" ]
echo "slurm-test: ok (a 2-task array rendered $n items; they equal the local run byte for byte)"
