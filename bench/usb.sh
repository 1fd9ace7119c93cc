#!/bin/sh
# bench/usb.sh BENCH_TXT — the section of docs/benchmarks.md for USB
# (make bench-usb): the lines "usb|tcp BYTES SECONDS" of the guest's
# throughput runs (tests/usb/guest-test.sh) as the median session
# throughput of each link and their ratio.
f=$1
med() {   # med KIND: median seconds of KIND's runs
    awk -v k="$1" '$1 == k { print $3 }' "$f" | sort -n | awk '{ a[NR] = $1 } END { print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2 }'
}
bytes=$(awk '{ print $2; exit }' "$f")
n=$(grep -c '^usb ' "$f")
u=$(med usb); t=$(med tcp)
cat <<EOT
## USB: lumo-server --usb to the gadget client over dummy_hcd, against TCP loopback

\`make bench-usb\`: in one QEMU x86-64 guest (TCG, Debian's kernel; tests/usb/), the
board client (boards/client, release build) streams the default scene from
lumo-server without drawing (\`--no-pictures\`), $n times over USB — the
FunctionFS gadget of boards/linux-gadget looped back through dummy_hcd to
lumo-server's libusb bridge — and $n times over TCP loopback, alternately. A run
is one session: $bytes bytes from HELLO to BYE with the client's fixed request
sizes (250 vertices, 4 lighting rounds, 4 in flight), so the figure is what a
real client gets through each link (round trips and the client's decoding
included), not raw bulk bandwidth. Seconds from the server's line per session
(10 ms steps); medians. The guest has one virtual CPU: over USB each byte
also crosses the bridge's pump threads, the gadget's reader thread and
dummy_hcd's 1 ms frame timer, all on that CPU under TCG.

| link | median session | throughput |
|---|---:|---:|
| USB (dummy_hcd, high speed) | $u s | $(awk -v b="$bytes" -v s="$u" 'BEGIN { printf "%.3f MB/s", b / s / 1e6 }') |
| TCP loopback | $t s | $(awk -v b="$bytes" -v s="$t" 'BEGIN { printf "%.3f MB/s", b / s / 1e6 }') |

Host load average when written: $(cut -d' ' -f1-3 /proc/loadavg) on $(nproc) cores (the guest's
timings move with it; the runs alternate so a burst hits both links).

USB / TCP throughput: **$(awk -v u="$u" -v t="$t" 'BEGIN { printf "%.2f", t / u }')** (every run: $(awk '{ printf "%s%s %s s", (NR > 1 ? ", " : ""), $1, $3 }' "$f")).
EOT
