#!/bin/sh
# A single-node SLURM on this machine, for `make test-cluster` (run as root; Debian/Ubuntu).
#   setup.sh start   install slurm-wlm and munge if missing, write slurm.conf for this host,
#                    start munged, slurmctld and slurmd, wait until the node is idle
#   setup.sh stop    stop the daemons that `start` started (and nothing else)
#   setup.sh status  sinfo
# Idempotent: `start` twice leaves one set of daemons; a slurm.conf not written by this script is
# never overwritten. SLURM_CGROUPS=auto (default) uses cgroups (proctrack/task cgroup, memory
# limits) if a job runs under them here, and falls back to no cgroups otherwise; yes|no forces it.
set -eu

CONF=/etc/slurm/slurm.conf
CGROUP_CONF=/etc/slurm/cgroup.conf
MARK="# written by FibrilFit .ci/slurm/setup.sh"
STATE=/run/fibrilfit-slurm          # which daemons `start` started
LOGS=/var/log/slurm
CGROUPS=${SLURM_CGROUPS:-auto}
PARTITION=${SLURM_PARTITION:-debug}

say() { echo "slurm-setup: $*"; }
die() { echo "slurm-setup: error: $*" >&2; exit 1; }

running() {  # running PIDFILE: the pid file names a live process
    [ -s "$1" ] && kill -0 "$(cat "$1")" 2>/dev/null
}

install_packages() {
    if command -v slurmctld >/dev/null && command -v slurmd >/dev/null \
            && command -v munged >/dev/null && command -v sinfo >/dev/null; then
        return
    fi
    [ "$(id -u)" = 0 ] || die "installing slurm-wlm and munge needs root"
    say "installing slurm-wlm and munge"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -q
    apt-get install -y -q --no-install-recommends slurm-wlm slurm-client munge
}

start_munge() {
    if [ ! -s /etc/munge/munge.key ]; then
        mungekey --create --keyfile=/etc/munge/munge.key
    fi
    chown munge:munge /etc/munge/munge.key && chmod 0400 /etc/munge/munge.key
    mkdir -p /run/munge /var/lib/munge /var/log/munge
    chown munge:munge /run/munge /var/lib/munge /var/log/munge
    if running /run/munge/munged.pid; then
        return
    fi
    say "starting munged"
    runuser -u munge -- /usr/sbin/munged
    echo munged >>"$STATE/started"
    munge -n | unmunge >/dev/null || die "munge does not work (see /var/log/munge/munged.log)"
}

write_conf() {  # write_conf yes|no
    node=$(slurmd -C | head -n 1)    # NodeName=<host> CPUs=.. Boards=.. ... RealMemory=..
    host=$(hostname -s)
    if [ "$1" = yes ]; then
        plugins="ProctrackType=proctrack/cgroup
TaskPlugin=task/cgroup
JobAcctGatherType=jobacct_gather/cgroup"
    else
        plugins="ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none"
    fi
    new=$(cat <<CONF
$MARK ($(date -u +%FT%TZ)); cgroups: $1
ClusterName=fibrilfit-test
SlurmctldHost=$host
SlurmUser=slurm
AuthType=auth/munge
StateSaveLocation=/var/lib/slurm/slurmctld
SlurmdSpoolDir=/var/lib/slurm/slurmd
SlurmctldPidFile=/run/slurmctld.pid
SlurmdPidFile=/run/slurmd.pid
SlurmctldLogFile=$LOGS/slurmctld.log
SlurmdLogFile=$LOGS/slurmd.log
$plugins
MpiDefault=none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
ReturnToService=2
KillWait=10
$node
PartitionName=$PARTITION Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
)
    if [ -e "$CONF" ] && ! head -n 1 "$CONF" | grep -q "^$MARK"; then
        die "$CONF exists and was not written by this script; not touching it"
    fi
    mkdir -p /etc/slurm /var/lib/slurm/slurmctld /var/lib/slurm/slurmd "$LOGS"
    chown slurm:slurm /var/lib/slurm/slurmctld "$LOGS"
    printf '%s\n' "$new" >"$CONF"
    if [ "$1" = yes ]; then
        printf '%s\n' "$MARK" "CgroupPlugin=autodetect" "ConstrainCores=yes" \
            "ConstrainRAMSpace=yes" >"$CGROUP_CONF"
    else
        rm -f "$CGROUP_CONF"
    fi
}

start_slurm() {
    if ! running /run/slurmctld.pid; then
        say "starting slurmctld"
        /usr/sbin/slurmctld
        echo slurmctld >>"$STATE/started"
    fi
    if ! running /run/slurmd.pid; then
        say "starting slurmd"
        /usr/sbin/slurmd
        echo slurmd >>"$STATE/started"
    fi
}

stop_slurm() {  # the SLURM daemons, whoever started them (used when reconfiguring)
    for d in slurmd slurmctld; do
        if running /run/$d.pid; then
            kill "$(cat /run/$d.pid)"
        fi
    done
    for _ in $(seq 100); do
        if ! running /run/slurmd.pid && ! running /run/slurmctld.pid; then
            rm -f /run/slurmd.pid /run/slurmctld.pid
            return 0
        fi
        sleep 0.2
    done
    die "slurmd/slurmctld did not stop"
}

wait_idle() {  # wait_idle SECONDS: until the node is idle; resume it if it is down or drained
    end=$(( $(date +%s) + $1 ))
    while [ "$(date +%s)" -lt "$end" ]; do
        state=$(sinfo -h -N -o %T 2>/dev/null | head -n 1 || true)
        case "$state" in
            idle) return 0 ;;
            down*|drain*|fail*)
                scontrol update nodename="$(hostname -s)" state=resume 2>/dev/null || true ;;
        esac
        sleep 1
    done
    say "node state after $1 s: '${state:-no answer}'"
    return 1
}

job_runs() {  # a one-second job, under the current configuration
    timeout 60 srun -N 1 -n 1 -t 1 --mem=50M sh -c 'sleep 1; echo ok' 2>&1 | grep -qx ok
}

configured() {  # configured yes|no: our slurm.conf with these cgroup settings is in place
    [ -e "$CONF" ] && head -n 1 "$CONF" | grep -q "^$MARK.*cgroups: $1\$"
}

bring_up() {  # bring_up yes|no
    if ! configured "$1"; then
        stop_slurm
        write_conf "$1"
    fi
    start_slurm
    wait_idle 60 && job_runs
}

start() {
    [ "$(id -u)" = 0 ] || die "run as root (it starts munged, slurmctld and slurmd)"
    install_packages
    mkdir -p "$STATE"
    start_munge
    case "$CGROUPS" in
        yes) bring_up yes || die "SLURM did not come up with cgroups (see $LOGS)" ;;
        no) bring_up no || die "SLURM did not come up (see $LOGS)" ;;
        auto)
            if configured no; then   # found out before, on this machine
                bring_up no || die "SLURM did not come up (see $LOGS)"
            elif ! bring_up yes; then
                say "no job runs with cgroups here; falling back to proctrack/linuxproc, no cgroups"
                bring_up no || die "SLURM did not come up (see $LOGS)"
            fi ;;
        *) die "SLURM_CGROUPS must be auto, yes or no (got '$CGROUPS')" ;;
    esac
    say "up: $(head -n 1 "$CONF" | sed 's/.*; //')"
    sinfo
}

stop() {
    [ -s "$STATE/started" ] || { say "nothing started by this script is running"; return 0; }
    for d in slurmd slurmctld munged; do
        grep -qx "$d" "$STATE/started" || continue
        pidfile=/run/$d.pid
        [ "$d" = munged ] && pidfile=/run/munge/munged.pid
        if running "$pidfile"; then
            say "stopping $d"
            kill "$(cat "$pidfile")"
            for _ in $(seq 100); do running "$pidfile" || break; sleep 0.2; done
            running "$pidfile" && die "$d (pid $(cat "$pidfile")) did not stop"
        fi
        rm -f "$pidfile"  # slurmctld leaves its pid file behind
    done
    rm -f "$STATE/started"
}

case "${1:-}" in
    start) start ;;
    stop) stop ;;
    status) sinfo ;;
    *) echo "usage: $0 start|stop|status" >&2; exit 2 ;;
esac
