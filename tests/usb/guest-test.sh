#!/bin/sh
# tests/usb/guest-test.sh — /test.sh of the USB guest (tests/usb/usb-test.sh
# builds the initramfs, boots it and reads these lines from the console).
# In the guest: /bin/lumo-server, /bin/lumo-gadget (boards/linux-gadget),
# /bin/lumo-client-tcp (the same client over TCP), /gadget.sh, /pkg.lumo
# and /ref.hash (the full scene's HASH lines from a host run of the same
# client over TCP). The gadget is looped back to the guest's own host side
# through dummy_hcd (dummy_udc.0).
#
#  1. clean: lumo-server --usb streams the package to the gadget client;
#     its pictures equal the TCP client's in the same guest, the full
#     scene's equal the host's.
#  2. two devices at once, one unplugged: with --rate (so the stream lasts
#     a few seconds) a second gadget (dummy_udc.1) streams beside the
#     first; the first's UDC is unbound once its first picture is drawn and
#     bound again 1 s later: the server ends that session only (the other
#     finishes on its one connection), claims the device when it comes
#     back, the client resumes with HELLO and its cursors; the full scene
#     again, nothing taken out of turn, the DATA bytes of the clean run
#     exactly, and the bytes received twice are only a WELCOME and any of a
#     frame the cut left.
#  3. throughput: the same client without pictures, USB and TCP loopback
#     alternately, lumo_runs=N runs each (kernel command line; default 2);
#     bytes / session time from the server's log lines ("USBTEST bench").
# Lines: "USBTEST ok: ...", "USBTEST bad: ...", "USBTEST RESULT: N passed,
# M failed".
pass=0
fail=0
ok() { pass=$((pass + 1)); echo "USBTEST ok: $*"; }
bad() { fail=$((fail + 1)); echo "USBTEST bad: $*"; }
export LUMO_FFS=/dev/ffs-lumo

# serve NAME ARGS...: lumo-server --usb in the background; $srv, and $tcp
# its TCP port.
serve() {
    name=$1; shift
    rm -f /tmp/port
    lumo-server /pkg.lumo --usb --listen 127.0.0.1:0 --port-file /tmp/port \
        "$@" 2>"/tmp/$name.server.log" &
    srv=$!
    i=0
    while [ ! -s /tmp/port ] && [ $i -lt 50 ]; do sleep 0.1; i=$((i + 1)); done
    tcp=$(cut -d' ' -f1 /tmp/port)
}

stop_server() {
    kill "$srv" 2>/dev/null
    wait "$srv" 2>/dev/null
}

# finish PID SECONDS: wait for PID at most SECONDS; its status in $st (124:
# killed at the deadline).
finish() {
    i=0
    while kill -0 "$1" 2>/dev/null && [ $i -lt $(($2 * 10)) ]; do sleep 0.1; i=$((i + 1)); done
    if kill -0 "$1" 2>/dev/null; then
        kill "$1"; wait "$1" 2>/dev/null; st=124
    else
        wait "$1"; st=$?
    fi
}

# gadget NAME ARGS...: the gadget client in the background ($cpid), the
# gadget bound once its descriptors are written.
gadget() {
    name=$1; shift
    sh /gadget.sh unbind
    lumo-gadget "$@" >"/tmp/$name.log" 2>"/tmp/$name.err" &
    cpid=$!
    if sh /gadget.sh wait && sh /gadget.sh bind dummy_udc.0; then
        return 0
    fi
    bad "$name: the gadget could not be bound"; cat "/tmp/$name.err"
    kill "$cpid" 2>/dev/null; wait "$cpid" 2>/dev/null
    return 1
}

field() {   # field LOG REGEX: the number before REGEX on the client's done line
    grep '^client: done' "$1" | sed -n "s/.* \([0-9][0-9]*\) $2.*/\1/p"
}

# 1. clean
sh /gadget.sh setup
serve clean
if gadget usb; then
    finish "$cpid" 40
    grep '^HASH' /tmp/usb.log >/tmp/usb.hash
    if [ "$st" -eq 0 ] && grep '^HASH frame-100' /tmp/usb.hash | cmp -s - /ref.hash; then
        ok "USB, clean: $(grep -c . /tmp/usb.hash) pictures, the full scene equals the host's; $(grep '^client: done' /tmp/usb.log | sed 's/^client: done: //')"
    else
        bad "USB, clean (exit $st)"; tail -n 5 /tmp/usb.log /tmp/usb.err
    fi
fi
LUMO_LINK=127.0.0.1:$tcp lumo-client-tcp >/tmp/tcp.log 2>&1 &
finish $! 40
grep '^HASH' /tmp/tcp.log >/tmp/tcp.hash
if [ "$st" -eq 0 ] && [ -s /tmp/usb.hash ] && cmp -s /tmp/usb.hash /tmp/tcp.hash; then
    ok "TCP in the same guest: the same $(grep -c . /tmp/tcp.hash) pictures as over USB"
else
    bad "TCP in the guest (exit $st): pictures differ from USB's"; diff /tmp/usb.hash /tmp/tcp.hash | head -n 6
fi
grep -q ' usb: HELLO .*: bye' /tmp/clean.server.log && ok "server: $(grep ' usb: HELLO' /tmp/clean.server.log | head -n 1 | sed 's/^lumo-server: //')" ||
    { bad "server: no USB session ended with BYE"; cat /tmp/clean.server.log; }
stop_server

# 2. two devices; one unplugged mid-stream and plugged back
export LUMO_GADGET=lumo2
sh /gadget.sh setup
serve unplug --rate 1000
sh /gadget.sh unbind
LUMO_FFS=/dev/ffs-lumo2 lumo-gadget >/tmp/other.log 2>/tmp/other.err &
opid=$!
sh /gadget.sh wait && sh /gadget.sh bind dummy_udc.1 || bad "the second gadget could not be bound"
export LUMO_GADGET=lumo
if gadget cut; then
    i=0
    while ! grep -q '^HASH frame-first' /tmp/cut.log && [ $i -lt 300 ]; do sleep 0.1; i=$((i + 1)); done
    if grep -q '^HASH frame-100' /tmp/cut.log; then
        bad "unplug: the scene was complete before the unplug (raise the load or lower --rate)"
    fi
    sh /gadget.sh unbind
    echo "USBTEST info: unbound after the first picture"
    sleep 1
    sh /gadget.sh bind dummy_udc.0
    finish "$cpid" 40
    cst=$st
    finish "$opid" 40
    grep '^HASH frame-100' /tmp/other.log >/tmp/other.hash
    if [ "$st" -eq 0 ] && cmp -s /tmp/other.hash /ref.hash && [ "$(field /tmp/other.log connections)" = 1 ]; then
        ok "the other device, beside the unplugged one: the full scene on its one connection"
    else
        bad "the other device (exit $st)"; tail -n 3 /tmp/other.log /tmp/other.err
    fi
    st=$cst
    grep '^HASH frame-100' /tmp/cut.log >/tmp/cut.hash
    data_a=$(field /tmp/usb.log 'DATA bytes'); data_b=$(field /tmp/cut.log 'DATA bytes')
    if [ "$st" -eq 0 ] && cmp -s /tmp/cut.hash /ref.hash; then
        ok "unplug: the full scene equals the host's after the cut"
    else
        bad "unplug (exit $st)"; tail -n 5 /tmp/cut.log /tmp/cut.err
    fi
    if [ "$(field /tmp/cut.log connections)" = 2 ] && [ "$(field /tmp/cut.log 'out of turn')" = 0 ] &&
       [ "$(field /tmp/cut.log refused)" = 0 ] && [ -n "$data_a" ] && [ "$data_a" = "$data_b" ]; then
        ok "unplug: resumed on the 2nd connection, nothing out of turn, $data_b DATA bytes as the clean run; received twice: $(grep '^client: done' /tmp/cut.log | sed -n 's/.*connections (\(.*\))$/\1/p')"
    else
        bad "unplug: not resumed cleanly: $(grep '^client: done' /tmp/cut.log) (clean run: $data_a DATA bytes)"
    fi
    if [ "$(grep -c ' usb: HELLO' /tmp/unplug.server.log)" = 3 ] && [ "$(grep -c ' usb: HELLO.* resume,' /tmp/unplug.server.log)" = 1 ] &&
       [ "$(grep -c ' usb: HELLO.*: bye$' /tmp/unplug.server.log)" = 2 ]; then
        ok "server: 3 USB sessions: the unplugged one ended alone ($(grep ' usb: HELLO' /tmp/unplug.server.log | grep -v ': bye$' | sed 's/.*: //')), the other and the resumed one to BYE"
    else
        bad "server: no resumed second session"; cat /tmp/unplug.server.log
    fi
fi
stop_server

# 3. throughput: bytes / session seconds from the server's lines
serve bench
runs=$(sed -n 's/.*lumo_runs=\([0-9]*\).*/\1/p' /proc/cmdline)
runs=${runs:-2}
for r in $(seq 1 "$runs"); do
    gadget "u$r" --no-pictures && finish "$cpid" 40
    LUMO_LINK=127.0.0.1:$tcp lumo-client-tcp --no-pictures >"/tmp/t$r.log" 2>&1 &
    finish $! 40
done
stop_server
grep -E ' (usb|tcp): HELLO' /tmp/bench.server.log |
    sed -n 's/.* \(usb\|tcp\): HELLO.* \([0-9]*\) bytes sent in .*, \([0-9.]*\) s: bye$/USBTEST bench \1 \2 \3/p'
[ "$(grep -c ': bye$' /tmp/bench.server.log)" = $((2 * runs)) ] && ok "throughput: $runs USB and $runs TCP sessions, each to BYE" ||
    { bad "throughput runs"; cat /tmp/bench.server.log; }
echo "USBTEST info: done at $(cut -d' ' -f1 /proc/uptime) s"
echo "USBTEST RESULT: $pass passed, $fail failed"
