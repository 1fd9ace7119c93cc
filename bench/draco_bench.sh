#!/bin/sh
# bench/draco_bench.sh BUILD — lumo's Draco decoder against libdraco 1.5.5
# in one run: decode time, callgrind instructions, memory, M3 code size.
# Writes BUILD/bench/sections/40-draco.md.
build=${1:-build}
bin="$build/bin"
work="$build/bench/draco"
out="$build/bench/sections/40-draco.md"
mkdir -p "$work" "$(dirname "$out")"
rows="$work/rows.md"; : > "$rows"
mrows="$work/mem.md"; : > "$mrows"

field() { echo "$1" | tr ' ' '\n' | sed -n "s/^$2=//p"; }

for size in 11k 48k 203k 871k; do
    ply="$build/data/models/dragon_$size.ply"
    [ -f "$ply" ] || continue
    case $size in 11k) reps=20 ;; 48k) reps=10 ;; 203k) reps=4 ;; *) reps=2 ;; esac
    for cl in 0 7 10; do
        drc="$work/dragon_${size}_cl$cl.drc"
        [ -f "$drc" ] || draco_encoder -i "$ply" -o "$drc" -cl "$cl" > /dev/null
        l=$("$bin/draco-bench" "$drc" $reps) || continue
        d=$("$bin/draco-bench-libdraco" "$drc" $reps) || continue
        li=$(valgrind --tool=callgrind --callgrind-out-file="$work/cg.out" \
             --toggle-collect=lumo_draco_decode "$bin/draco-bench" "$drc" 1 2>&1 >/dev/null |
             sed -n 's/.*Collected : \([0-9]*\).*/\1/p' | tail -1)
        di=$(valgrind --tool=callgrind --callgrind-out-file="$work/cg.out" \
             --toggle-collect='draco::Decoder::DecodeMeshFromBuffer*' \
             "$bin/draco-bench-libdraco" "$drc" 1 2>&1 >/dev/null |
             sed -n 's/.*Collected : \([0-9]*\).*/\1/p' | tail -1)
        fi=$(valgrind --tool=callgrind --callgrind-out-file="$work/cg.out" \
             --toggle-collect='draco::Decoder::DecodeMeshFromBuffer*' \
             "$bin/draco-bench-libdraco" "$drc" 1 full 2>&1 >/dev/null |
             sed -n 's/.*Collected : \([0-9]*\).*/\1/p' | tail -1)
        lns=$(field "$l" ns); dns=$(field "$d" ns)
        faces=$(field "$l" faces); o=$(field "$l" out); ar=$(field "$l" arena)
        nd=$(field "$l" need); ex=$(field "$l" exact)
        heap=$(field "$d" heap_peak)
        awk -v s="$size" -v cl="$cl" -v f="$faces" -v lns="$lns" -v dns="$dns" -v li="$li" -v di="$di" -v fi="$fi" \
            'BEGIN { printf "| %s | %d | %d | %.2f | %.2f | %.2fx | %.1f | %.1f | %.2fx | %.1f | %.2fx |\n",
                     s, cl, f, lns / 1e6, dns / 1e6, dns / lns, li / 1e6, di / 1e6, di / li, fi / 1e6, fi / li }' >> "$rows"
        awk -v s="$size" -v cl="$cl" -v f="$faces" -v o="$o" -v ar="$ar" -v h="$heap" -v nd="$nd" -v ex="$ex" \
            'BEGIN { printf "| %s | %d | %.2f | %.2f | %.2fx | %.1f | %.2f (%s) | %.3fx | %.2f | %.1f |\n",
                     s, cl, o / 1e6, ar / 1e6, ar / o, ar / f, nd / 1e6, ex ? "exact" : "bound", nd / ar, h / 1e6, h / f }' >> "$mrows"
    done
done

{
    echo "## Draco decoder (issue 4): lumo vs libdraco 1.5.5"
    echo
    echo "Command: \`make bench-draco\` (bench/draco_bench.sh; streams from \`draco_encoder -cl N\` on"
    echo "build/data/models/dragon_*.ply, default quantization). Both decoders produce the portable"
    echo "integers (libdraco with \`SetSkipAttributeTransform\`); lumo host build -O2, libdraco the"
    echo "Debian 1.5.5 package. Time: best of N decodes; instructions: callgrind inside"
    echo "\`lumo_draco_decode\` / \`draco::Decoder::DecodeMeshFromBuffer\`."
    echo
    echo "The last two columns: libdraco's full decode (attribute transforms to float, as"
    echo "\`draco_decoder\` runs it) against lumo's portable decode."
    echo
    echo "| dragon | cl | faces | lumo ms | libdraco ms | speed-up | lumo Minstr | libdraco Minstr | instr ratio | libdraco full Minstr | full ratio |"
    echo "|---|---|---|---|---|---|---|---|---|---|---|"
    cat "$rows"
    echo
    echo "Memory: lumo's decoded output (faces + portable values + point maps) and the exact arena"
    echo "a decode needs (outputs + peak work memory, \`arena_bytes + work_bytes\`), against"
    echo "libdraco's peak heap (global operator new, same decode). \"need before decoding\" is"
    echo "\`lumo_draco_arena_need()\`, computed from the stream before decoding (the arena every"
    echo "decode here was given), and its ratio to the exact arena."
    echo
    echo "| dragon | cl | output MB | lumo arena MB | arena/output | arena B/face | need before decoding MB | need/arena | libdraco heap MB | heap B/face |"
    echo "|---|---|---|---|---|---|---|---|---|---|"
    cat "$mrows"
    echo
    echo "Cortex-M3 code size of the decoder (\`arm-none-eabi-size build/m3/sdk/src/draco_*.o\`, -Os):"
    echo
    echo '```'
    arm-none-eabi-size -t "$build"/m3/sdk/src/draco_*.o
    echo '```'
} > "$out"
echo "bench-draco: wrote $out"
