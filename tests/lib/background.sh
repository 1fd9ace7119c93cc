# tests/lib/background.sh — sourced by the end-to-end test scripts that run
# servers and proxies in the background (tests/serve, tests/client,
# boards/client): the pass/fail counters, a trap that kills every process
# they started (nothing is left behind, whatever happens), and waiting for a
# listener's port file. POSIX sh.
pass=0; fail=0
ok()  { pass=$((pass + 1)); echo "ok   $1"; }
bad() { fail=$((fail + 1)); echo "FAIL $1"; }

pids=""
# TERM first: `timeout` passes it on to its command (a SIGKILL would leave
# the command running as an orphan); then KILL whatever is left.
cleanup() {
    for p in $pids; do kill "$p" 2>/dev/null; done
    sleep 0.2
    for p in $pids; do kill -9 "$p" 2>/dev/null; done
}
trap cleanup EXIT
trap 'cleanup; exit 1' INT TERM

# spawn NAME PORTFILE LOG CMD...: CMD in the background, its stderr in LOG
# (it writes its port numbers into PORTFILE once it listens); sets $pid and
# adds it to the processes the trap kills. Returns 0 once PORTFILE is
# written (5 s at most), else says why in a FAIL line with LOG.
spawn() {
    sp_name=$1; sp_file=$2; sp_log=$3; shift 3
    rm -f "$sp_file"
    "$@" 2>"$sp_log" &
    pid=$!
    pids="$pids $pid"
    sp_i=0
    while [ ! -s "$sp_file" ] && [ $sp_i -lt 50 ]; do sleep 0.1; sp_i=$((sp_i + 1)); done
    [ -s "$sp_file" ] && return 0
    bad "$sp_name: did not start"; sed 's/^/    /' "$sp_log"
    return 1
}
