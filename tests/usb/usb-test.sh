#!/bin/sh
# tests/usb/usb-test.sh DIR PACKAGE SERVER GADGET TCP_CLIENT HOST_CLIENT — the
# USB transport for real, in a QEMU x86-64 guest running Debian's kernel
# (docs/protocol.md §8 "USB", docs/porting.md §9):
#  1. the reference: HOST_CLIENT (boards/client on the Linux board, ASan)
#     streams PACKAGE from SERVER over TCP on this machine; its full-scene
#     HASH lines are what the guest's runs must show;
#  2. the kernel (tests/usb/kernel.sh, cached under DIR/kernel) and an
#     initramfs (tests/usb/initramfs.sh) with SERVER, GADGET, TCP_CLIENT,
#     boards/linux-gadget/gadget.sh, the package and the reference;
#  3. the guest runs tests/usb/guest-test.sh (clean run, unplug and
#     resume beside a second device, USB_RUNS throughput pairs, default
#     2) under qemu-system-x86_64 -accel tcg, at most 150 s (+10 s a pair
#     beyond 2); its "USBTEST" lines are read from the console log.
# QEMU's exit status does not carry the verdict: the guest's RESULT line
# does. Prints "RESULT: N passed, M failed"; the throughput lines go to
# DIR/bench.txt (bench/usb.sh formats them). Logs: DIR/*.log.
set -u
dir=$1; pkg=$2; server=$3; gadget=$4; tcpc=$5; host=$6
here=$(dirname "$0")
mkdir -p "$dir"
. "$here/../lib/background.sh"

# 1. the reference, on this machine
if spawn "reference: lumo-server" "$dir/ref.port" "$dir/ref.server.log" "$server" "$pkg" --listen 127.0.0.1:0 \
         --port-file "$dir/ref.port"; then
    LUMO_LINK=127.0.0.1:$(cut -d' ' -f1 "$dir/ref.port") timeout 120 "$host" >"$dir/ref.log" 2>&1 </dev/null
    grep '^HASH frame-100' "$dir/ref.log" >"$dir/ref.hash"
fi
if [ "$(grep -c . "$dir/ref.hash" 2>/dev/null)" = 2 ]; then
    ok "reference on this machine over TCP: $(tr '\n' ' ' <"$dir/ref.hash")"
else
    bad "reference run — $dir/ref.log"; tail -n 5 "$dir/ref.log" | sed 's/^/    /'
    echo "RESULT: $pass passed, $fail failed"; exit 1
fi

# 2. kernel and initramfs
if ! kroot=$(sh "$here/kernel.sh" "$dir/kernel"); then
    bad "no kernel for the guest"; echo "RESULT: $pass passed, $fail failed"; exit 1
fi
cp "$pkg" "$dir/pkg.lumo"
cp "$dir/ref.hash" "$dir/ref.hash.tmp" && mv "$dir/ref.hash.tmp" "$dir/ref.hash"
if ! sh "$here/initramfs.sh" "$dir/initramfs.gz" "$kroot" "$here/guest-test.sh" "$server" "$gadget" "$tcpc" \
        "$here/../../boards/linux-gadget/gadget.sh" "$dir/pkg.lumo" "$dir/ref.hash" 2>"$dir/initramfs.log"; then
    bad "initramfs — $dir/initramfs.log"; echo "RESULT: $pass passed, $fail failed"; exit 1
fi

# 3. boot
runs=${USB_RUNS:-2}
limit=$((150 + (runs > 2 ? runs - 2 : 0) * 10))
timeout $limit qemu-system-x86_64 -accel tcg -m 512 -nographic -no-reboot -kernel "$kroot"/boot/vmlinuz-* \
    -initrd "$dir/initramfs.gz" -append "console=ttyS0 panic=-1 quiet lumo_runs=$runs" </dev/null >"$dir/console.log" 2>&1 &
q=$!
pids="$pids $q"
wait $q
qst=$?
tr -d '\r' <"$dir/console.log" >"$dir/console.txt"
grep '^USBTEST \(ok\|bad\|info\)' "$dir/console.txt" | sed 's/^USBTEST /    guest /'
grep '^USBTEST bench ' "$dir/console.txt" | sed 's/^USBTEST bench //' >"$dir/bench.txt"
res=$(sed -n 's/^USBTEST RESULT: \([0-9]*\) passed, \([0-9]*\) failed$/\1 \2/p' "$dir/console.txt")
if [ -n "$res" ] && [ "${res#* }" = 0 ] && [ "${res% *}" -ge 8 ]; then
    ok "QEMU guest (Debian kernel, dummy_hcd): ${res% *} checks passed; throughput runs in $dir/bench.txt"
elif [ -n "$res" ]; then
    bad "QEMU guest: ${res#* } of its checks failed — $dir/console.txt"
else
    bad "QEMU guest: no result line (QEMU status $qst; timeout $limit s) — $dir/console.txt"
    tail -n 15 "$dir/console.txt" | sed 's/^/    /'
fi
echo "RESULT: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
