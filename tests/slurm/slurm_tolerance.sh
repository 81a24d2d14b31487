#!/usr/bin/env bash
# CTest slurm.tolerance: a single-node Slurm cluster (slurmctld + slurmd + munge, Debian's
# packages, generated slurm.conf on private ports and paths) runs a 4-shard tolerance job
# through `fovea-cli tolerance --slurm DIR --submit`; the merged result must equal the local
# run byte for byte. Stops the daemons it started (by PID). Exit 77 (skipped) when not root.
# usage: slurm_tolerance.sh FOVEA_CLI SPEC WORKDIR
set -euo pipefail
CLI=$1 SPEC=$2 WORK=$3
if [ "$(id -u)" -ne 0 ]; then echo "slurm test: needs root (skipped)"; exit 77; fi

need=()
for p in slurmctld slurmd slurm-client munge; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || need+=("$p")
done
if [ ${#need[@]} -gt 0 ]; then
  echo "slurm test: installing ${need[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq && apt-get install -y -qq --no-install-recommends "${need[@]}" >/dev/null
fi

rm -rf "$WORK"
mkdir -p "$WORK"/{munge,munge-run,state,spool,log,job}
chown munge:munge "$WORK/munge" "$WORK/munge-run"
chmod 700 "$WORK/munge"
chmod 755 "$WORK/munge-run"  # munged wants the socket's directory searchable by all
PIDS=()
cleanup() {
  for p in "${PIDS[@]}"; do kill "$p" 2>/dev/null || true; done
  for p in "${PIDS[@]}"; do wait "$p" 2>/dev/null || true; done
}
trap cleanup EXIT

# munge on a private socket with a key of its own.
KEY="$WORK/munge/munge.key"
dd if=/dev/urandom of="$KEY" bs=1024 count=1 status=none
chown munge:munge "$KEY"
chmod 400 "$KEY"
SOCK="$WORK/munge-run/munge.socket"
su -s /bin/sh munge -c "/usr/sbin/munged --foreground --key-file=$KEY --socket=$SOCK \
  --pid-file=$WORK/munge-run/munged.pid --log-file=$WORK/munge/munged.log --seed-file=$WORK/munge/seed" &
PIDS+=($!)
for _ in $(seq 50); do [ -S "$SOCK" ] && break; sleep 0.1; done
[ -S "$SOCK" ] || { echo "slurm test: munged did not start"; cat "$WORK/munge/munged.log" || true; exit 1; }
PIDS+=("$(cat "$WORK/munge-run/munged.pid")")  # su's child: stopped by its own PID

HOST=$(hostname -s)
PORT=$((20000 + RANDOM % 20000))
CONF="$WORK/slurm.conf"
cat > "$CONF" <<CONFEOF
ClusterName=foveatest
SlurmctldHost=$HOST
SlurmctldPort=$PORT
SlurmdPort=$((PORT + 1))
SlurmUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$SOCK
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
JobAcctGatherType=jobacct_gather/none
StateSaveLocation=$WORK/state
SlurmdSpoolDir=$WORK/spool
SlurmctldPidFile=$WORK/state/slurmctld.pid
SlurmdPidFile=$WORK/spool/slurmd.pid
SlurmctldLogFile=$WORK/log/slurmctld.log
SlurmdLogFile=$WORK/log/slurmd.log
ReturnToService=2
NodeName=$HOST CPUs=$(nproc) State=UNKNOWN
PartitionName=test Nodes=$HOST Default=YES MaxTime=INFINITE State=UP
CONFEOF
export SLURM_CONF="$CONF"
/usr/sbin/slurmctld -D -i -f "$CONF" > "$WORK/log/slurmctld.out" 2>&1 &
PIDS+=($!)
sleep 1
/usr/sbin/slurmd -D -f "$CONF" > "$WORK/log/slurmd.out" 2>&1 &
PIDS+=($!)
up=0
for _ in $(seq 60); do
  if sinfo -h -o "%t" 2>/dev/null | grep -qE "idle|mix"; then up=1; break; fi
  sleep 0.5
done
if [ $up -ne 1 ]; then
  echo "slurm test: the node did not come up"; sinfo || true; tail -n 20 "$WORK"/log/* || true; exit 1
fi

ARGS=(tolerance --spec "$SPEC" --trials 16 --seed 5)
"$CLI" "${ARGS[@]}" --json > "$WORK/local.json"
"$CLI" "${ARGS[@]}" --slurm "$WORK/job" --shards 4 --submit --poll-seconds 1 --timeout-seconds 240 --json \
  > "$WORK/slurm.json"
for k in 0 1 2 3; do [ -s "$WORK/job/part-$k.json" ] || { echo "slurm test: part $k missing"; exit 1; }; done
if ! cmp "$WORK/local.json" "$WORK/slurm.json"; then
  echo "slurm test: merged result differs from the local run"; exit 1
fi
echo "slurm test: 4-shard job merged == local run ($(wc -c < "$WORK/local.json") bytes)"
