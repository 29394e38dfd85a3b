#!/usr/bin/env bash
# A real SLURM cluster on this one machine, for tests: munged, slurmctld and two slurmd
# (nodes n1 and n2, one CPU each, partition `debug`), everything under one run directory.
#
#   tests/cluster/slurm.sh up       install slurm-wlm + munge if missing, start, wait until idle
#   tests/cluster/slurm.sh down     cancel every job, stop the four daemons (idempotent)
#   tests/cluster/slurm.sh status   sinfo of the cluster
#
# Environment:
#   BBB_SLURM_DIR   run directory (default bbb-slurm in the temporary directory): slurm.conf, munge key and socket,
#                   state, spool, pid and log files; `up` writes $BBB_SLURM_DIR/env, which
#                   clients source (it exports SLURM_CONF) -- nothing under /etc is written
#   BBB_SLURM_PORT  slurmctld's port (default 16817); n1 and n2 listen on the next two
#   BBB_SLURM_WAIT  seconds `up` waits for both nodes to be idle (default 60)
#   BBB_SLURM_APT_TIMEOUT  seconds each apt-get step may take when installing (default 600)
#
# Needs root (slurmd runs jobs as their submitters; apt-get installs the packages).
# `up` on a directory whose cluster is still running stops that one first: every `up` starts
# a fresh cluster with an empty queue.  Only daemons named in the directory's pid files are
# ever stopped.
set -euo pipefail

DIR=${BBB_SLURM_DIR:-$(dirname "$(mktemp -u)")/bbb-slurm}
PORT=${BBB_SLURM_PORT:-16817}
WAIT=${BBB_SLURM_WAIT:-60}
APT_TIMEOUT=${BBB_SLURM_APT_TIMEOUT:-600}
CONF=$DIR/slurm.conf
DAEMONS=(slurmd-n1 slurmd-n2 slurmctld munged)
declare -A STARTED=()  # daemon -> pid, of those `up` started

say() { echo "slurm.sh: $*" >&2; }
die() { say "error: $*"; exit 1; }

pidfile() { echo "$DIR/run/$1.pid"; }
logfile() { echo "$DIR/log/$1.log"; }
# what to read when daemon $1 fails (munged -F logs to its stderr only)
logs() {
    if [[ $1 == munged ]]; then echo "$DIR/log/munged.out"; else echo "$DIR/log/$1.log and $DIR/log/$1.out"; fi
}

# the pid of daemon $1 if its pid file names a live process running that program, else nothing
live_pid() {
    local f pid
    f=$(pidfile "$1")
    [[ -s $f ]] || return 0
    pid=$(<"$f")
    [[ $pid =~ ^[0-9]+$ ]] || return 0
    alive "$pid" "${1%%-*}" && echo "$pid"
    return 0
}

client() { SLURM_CONF=$CONF "$@"; }

install_packages() {
    command -v slurmctld >/dev/null && command -v munged >/dev/null && return 0
    say "slurmctld or munged not found: installing slurm-wlm and munge with apt-get"
    command -v apt-get >/dev/null || die "slurm-wlm and munge are not installed and there is no apt-get: install them by hand"
    export DEBIAN_FRONTEND=noninteractive
    timeout "$APT_TIMEOUT" apt-get update -qq >"$DIR/log/apt-get.log" 2>&1 ||
        die "apt-get update failed or took over ${APT_TIMEOUT}s (the package registry unreachable?): read $DIR/log/apt-get.log"
    timeout "$APT_TIMEOUT" apt-get install -y -qq slurm-wlm munge >>"$DIR/log/apt-get.log" 2>&1 ||
        die "apt-get install slurm-wlm munge failed or took over ${APT_TIMEOUT}s: read $DIR/log/apt-get.log"
    # the packages' own services (if an init system started them) are not this cluster's
}

write_conf() {
    cat >"$CONF" <<EOF
# written by tests/cluster/slurm.sh: a one-machine test cluster
ClusterName=bbbtest
SlurmctldHost=localhost
SlurmctldPort=$PORT
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$DIR/munge/munge.socket
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SwitchType=switch/none
MpiDefault=none
ReturnToService=2
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/none
StateSaveLocation=$DIR/state
SlurmdSpoolDir=$DIR/spool/%n
SlurmctldPidFile=$(pidfile slurmctld)
SlurmdPidFile=$DIR/run/slurmd-%n.pid
SlurmctldLogFile=$(logfile slurmctld)
SlurmdLogFile=$DIR/log/slurmd-%n.log
PlugStackConfig=$DIR/plugstack.conf
NodeName=n1 NodeHostname=localhost NodeAddr=127.0.0.1 Port=$((PORT + 1)) CPUs=1 RealMemory=256 State=UNKNOWN
NodeName=n2 NodeHostname=localhost NodeAddr=127.0.0.1 Port=$((PORT + 2)) CPUs=1 RealMemory=256 State=UNKNOWN
PartitionName=debug Nodes=n1,n2 Default=YES MaxTime=INFINITE State=UP
EOF
    : >"$DIR/plugstack.conf"  # not Debian's /etc/slurm/plugstack.conf
    echo "export SLURM_CONF=$CONF" >"$DIR/env"
}

# start daemon $1 (its name) in the foreground of a session of its own: the command is the rest;
# its stdout and stderr go to log/$1.out (slurm daemons also write their own log/$1.log)
start() {
    local name=$1
    shift
    setsid "$@" >>"$DIR/log/$name.out" 2>&1 </dev/null &
    STARTED[$name]=$!
    echo $! >"$(pidfile "$name")"  # the daemon writes the same pid there itself
}

node_states() { client sinfo -h -N -o '%N %t' 2>/dev/null | sort -u | tr '\n' ' '; }

wait_idle() {
    local deadline=$((SECONDS + WAIT)) d
    while ((SECONDS < deadline)); do
        for d in "${DAEMONS[@]}"; do
            # (kill -0: right after the fork the process is still bash or setsid, not $d)
            kill -0 "${STARTED[$d]}" 2>/dev/null || die "$d exited while starting: read $(logs "$d")"
        done
        [[ $(node_states) == "n1 idle n2 idle " ]] && return 0
        sleep 0.2
    done
    die "n1 and n2 not idle after ${WAIT}s (sinfo: $(node_states)); read $(logs slurmctld)," \
        "$(logs slurmd-n1), $(logs slurmd-n2)"
}

up() {
    [[ $EUID -eq 0 ]] || die "must run as root (slurmd runs jobs as their submitters)"
    mkdir -p "$DIR"
    down_all
    rm -rf "$DIR/state" "$DIR/spool" "$DIR/run" "$DIR/log" "$DIR/env"
    mkdir -p "$DIR/state" "$DIR/spool/n1" "$DIR/spool/n2" "$DIR/run" "$DIR/log"
    mkdir -p "$DIR/munge"
    # every user's clients must reach the munge socket; the key itself is 0600
    chmod 0755 "$DIR" "$DIR/munge" "$DIR/spool" "$DIR/spool/n1" "$DIR/spool/n2"
    install_packages
    trap 'say "up failed: stopping what it started"; down_all' EXIT
    if [[ ! -s $DIR/munge/munge.key ]]; then
        say "creating the munge key $DIR/munge/munge.key"
        (umask 077 && head -c 1024 /dev/urandom >"$DIR/munge/munge.key")
    fi
    write_conf
    local m=$DIR/munge
    start munged munged -F --socket="$m/munge.socket" --key-file="$m/munge.key" \
        --pid-file="$(pidfile munged)" --seed-file="$m/munge.seed"  # -F: it logs to munged.out
    local i  # wait until it answers (a socket left by an earlier munged may still be there)
    for ((i = 0; i < 100; i++)); do
        munge -n -S "$m/munge.socket" 2>/dev/null | unmunge -S "$m/munge.socket" >/dev/null 2>&1 && break
        kill -0 "${STARTED[munged]}" 2>/dev/null || die "munged exited while starting: read $(logs munged)"
        sleep 0.1
    done
    ((i < 100)) || die "munged does not answer after 10 s: read $(logs munged)"
    start slurmctld slurmctld -D -f "$CONF"
    start slurmd-n1 slurmd -D -N n1 -f "$CONF"
    start slurmd-n2 slurmd -D -N n2 -f "$CONF"
    wait_idle
    trap - EXIT
    say "up: nodes n1 n2 idle in partition debug; for clients: source $DIR/env"
    cat "$DIR/env"
}

# is pid $1 still program $2 (not exited, not reused)?
alive() { [[ $(cat "/proc/$1/comm" 2>/dev/null) == "$2" ]]; }

# stop the daemons named (TERM, then KILL after 10 s), all at once: each takes ~2 s to exit.
# Returns once every process is gone (the daemons remove their own pid files before they exit)
stop() {
    local d pid i
    local -A pids=()
    for d in "$@"; do
        pid=$(live_pid "$d")
        if [[ -n $pid ]]; then
            pids[$d]=$pid
            if ! kill -TERM "$pid" 2>/dev/null && alive "$pid" "${d%%-*}"; then
                die "cannot signal $d (pid $pid): run as its owner (root)"
            fi
        fi
    done
    for ((i = 0; i < 100; i++)); do
        for d in "${!pids[@]}"; do alive "${pids[$d]}" "${d%%-*}" || unset "pids[$d]"; done
        ((${#pids[@]} == 0)) && break
        sleep 0.1
    done
    for d in "${!pids[@]}"; do
        say "$d (pid ${pids[$d]}) ignored SIGTERM for 10 s: SIGKILL"
        kill -KILL "${pids[$d]}" 2>/dev/null || true
        for ((i = 0; i < 50; i++)); do
            alive "${pids[$d]}" "${d%%-*}" || break
            sleep 0.1
        done
        alive "${pids[$d]}" "${d%%-*}" && die "cannot stop $d (pid ${pids[$d]}): not its owner?"
    done
    for d in "$@"; do rm -f "$(pidfile "$d")"; done
}

down_all() {
    local jobs i
    if [[ -n $(live_pid slurmctld) && -f $CONF ]]; then
        # jobs' slurmstepd outlive slurmd: end the jobs while the cluster can still do it
        jobs=$(client squeue -h -o %i 2>/dev/null || true)
        if [[ -n $jobs ]]; then
            # shellcheck disable=SC2086
            client scancel $jobs 2>/dev/null || true
            for ((i = 0; i < 100; i++)); do
                [[ -z $(client squeue -h -o %i 2>/dev/null || true) ]] && break
                sleep 0.1
            done
        fi
    fi
    stop "${DAEMONS[@]}"
    kill_orphan_steps
}

# slurmstepd (and the job under it) outlive slurmd: those of this cluster that the scancel
# above did not end (slurmctld was dead, or a job ignored it) are found by the slurmd log file
# they hold open, and killed with everything below them
kill_orphan_steps() {
    local pid ppid fd i
    local -a steps=() doomed=()
    local -A children=()
    for pid in $(ps -C slurmstepd -o pid= || true); do
        for fd in /proc/"$pid"/fd/*; do
            if [[ $(readlink "$fd" 2>/dev/null) == "$DIR/log/slurmd-"* ]]; then
                steps+=("$pid")
                break
            fi
        done
    done
    ((${#steps[@]})) || return 0
    say "killing ${#steps[@]} slurmstepd left by jobs of this cluster (pids ${steps[*]}) and their jobs"
    while read -r pid ppid; do children[$ppid]+=" $pid"; done < <(ps -e -o pid=,ppid=)
    doomed=("${steps[@]}")
    for ((i = 0; i < ${#doomed[@]}; i++)); do
        pid=${doomed[$i]}
        # shellcheck disable=SC2206
        [[ -n ${children[$pid]:-} ]] && doomed+=(${children[$pid]})
    done
    kill -KILL "${doomed[@]}" 2>/dev/null || true
}

case ${1:-} in
    up) up ;;
    down) down_all ;;
    status)
        [[ -n $(live_pid slurmctld) ]] || die "no slurmctld running for $DIR"
        client sinfo
        ;;
    *) die "usage: $0 up|down|status   (run directory \$BBB_SLURM_DIR, default bbb-slurm in the temporary directory)" ;;
esac
