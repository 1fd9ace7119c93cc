#!/bin/sh
# bench/m3_profile.sh ELF MARK OUT [TOP] — where a board program's
# instructions go on the emulated Cortex-M3, per function and per
# translation block, split into sections at each entry of function MARK.
#
# Method: QEMU's own logging, no plugin (Debian's qemu-system-arm ships no
# TCG plugins): -d in_asm prints every translation block (TB) once with its
# instructions, -d exec,nochain one line per executed TB (nochain: chained
# TBs would skip the line). Instructions of a TB execution = its length;
# summed per function (QEMU names the symbol) and per TB start address
# (for addr2line). Section k counts what ran after the k-th entry of MARK
# (e.g. lumo_raster_clear: one section per frame; section 0 is the set-up
# before the first). Exact up to TBs left early by an exception (the
# board's timer interrupt: a few per frame). The log streams through a fifo:
# a per-pixel frame is tens of millions of TB lines.
#
# OUT/sections.txt: "section function instructions"; OUT/tbs.txt: "section
# pc instructions function" for the TOP (default 40) costliest TBs of each
# section, with their source line(s) (addr2line -i) in OUT/tbs_src.txt.
elf=$1; mark=$2; out=$3; top=${4:-40}
qemu=${QEMU_CMD:-qemu-system-arm -machine mps2-an385 -cpu cortex-m3 -nographic -monitor none -serial none -semihosting-config enable=on,target=native}
a2l=${ADDR2LINE:-arm-none-eabi-addr2line}
mkdir -p "$out"
fifo="$out/trace.fifo"
rm -f "$fifo"
mkfifo "$fifo"
awk -v mark="$mark" -v top="$top" -v out="$out" '
BEGIN { sec = 0 }
/^IN: / { fn = $2; start = ""; next }
/^0x[0-9a-f]+:/ {
    pc = substr($1, 1, length($1) - 1)
    if (start == "") { start = pc; len[start] = 0; name[start] = fn }
    len[start]++
    next
}
/^$/ { start = ""; next }
/^Trace / {
    split($0, f, "/"); pc = "0x" f[2]; fn = $NF
    if (fn == mark && pc == entry) sec++
    if (entry == "" && fn == mark) { entry = pc; sec++ }
    n = len[pc]
    byfn[sec, fn] += n; bytb[sec, pc] += n; secs[sec] = 1; tbname[pc] = fn
    next
}
END {
    for (k in byfn) { split(k, p, SUBSEP); print p[1], p[2], byfn[k] > (out "/sections.txt") }
    for (k in bytb) { split(k, p, SUBSEP); print p[1], p[2], bytb[k], tbname[p[2]] > (out "/tbs.all") }
}' "$fifo" &
awk_pid=$!
timeout 600 $qemu -d in_asm,exec,nochain -D "$fifo" -kernel "$elf" </dev/null >"$out/console.log" 2>&1
wait $awk_pid
rm -f "$fifo"
sort -k1,1n -k3,3nr "$out/sections.txt" -o "$out/sections.txt"
sort -k1,1n -k3,3nr "$out/tbs.all" | awk -v top="$top" '{ if ($1 != s) { s = $1; n = 0 } if (n++ < top) print }' >"$out/tbs.txt"
rm -f "$out/tbs.all"
: >"$out/tbs_src.txt"
while read -r sec pc n fn; do
    echo "$sec $pc $n $fn: $($a2l -i -e "$elf" "$pc" | sed 's|.*/rasterizer/|rasterizer/|;s|^/work/[^ ]*/\([a-z]\)|\1|' | tr '\n' ' ')" >>"$out/tbs_src.txt"
done <"$out/tbs.txt"
echo "sections: $(awk '{print $1}' "$out/sections.txt" | sort -un | tr '\n' ' ')"
