#!/bin/sh
# bench/draco_attrs.sh BUILD [quick] — lumo's Draco decoder against libdraco
# 1.5.5 on the attribute set of issue 25: seven meshes (not the dragons;
# tests/draco/gen_attr_meshes.cc: normals and texture coordinates by
# assimp, colours synthesised) x positions+normals / +texture coordinates /
# +colours x draco_encoder -cl 4, 7, 10 x two quantizations (the default
# -qp 11 -qt 10 -qn 8, and -qp 14 -qt 12 -qn 10): 126 streams.
# Instructions: callgrind inside the decode call, one valgrind run per
# decoder over all streams (draco-set-bench*, dumps per file); memory:
# native runs. `quick`: the -qp 14 streams at -cl 7 only (21 rows).
# Writes BUILD/bench/sections/41-draco-attrs.md.
build=${1:-build}; mode=${2:-full}
bin="$build/bin"
work="$build/bench/draco-attrs"
out="$build/bench/sections/41-draco-attrs.md"
mkdir -p "$work/attr" "$(dirname "$out")"
"$bin/gen-attr-meshes" "$work/attr" "$build/data/models/bunny.obj" || exit 1
files=""
for m in scan_20k scan_82k terrain cad holed parts bunny; do for k in n nt c; do
    case $k in c) src="$work/attr/${m}_c.ply" ;; *) src="$work/attr/${m}_$k.obj" ;; esac
    for q in 1 2; do for cl in 4 7 10; do
        [ "$mode" = quick ] && { [ $q = 2 ] && [ $cl = 7 ] || continue; }
        case $q in 1) qo="" ;; 2) qo="-qp 14 -qt 12 -qn 10" ;; esac
        drc="$work/${m}_${k}_q${q}_cl$cl.drc"
        [ -f "$drc" ] || draco_encoder -i "$src" -o "$drc" -cl $cl $qo > /dev/null || exit 1
        files="$files $drc"
    done; done
done; done

# instructions per file: "<file> <Ir>" from the per-file dumps
instr() {  # instr OUT PROGRAM ARGS...
    o=$1; shift
    rm -f "$work"/cg.out*
    valgrind --tool=callgrind --collect-atstart=no --callgrind-out-file="$work/cg.out" \
        "$@" > /dev/null 2> "$work/cg.log" || { cat "$work/cg.log"; exit 1; }
    for f in "$work"/cg.out.*; do
        awk '/^desc: Trigger: Client Request: / { sub(/^desc: Trigger: Client Request: /, ""); n = $0 }
             /^totals: / { t = $2 } END { print n, t }' "$f"
    done > "$o"
}
"$bin/draco-set-bench" $files > "$work/mem.txt" || exit 1
"$bin/draco-set-bench" lean $files > "$work/mem_lean.txt" || exit 1
"$bin/draco-set-bench-libdraco" $files > "$work/heap.txt" || exit 1
instr "$work/ir.txt" "$bin/draco-set-bench" $files
instr "$work/ir_lean.txt" "$bin/draco-set-bench" lean $files
instr "$work/ir_lib.txt" "$bin/draco-set-bench-libdraco" $files

# summary ROWS: per attributes and level, ranges of the four ratios
summary() {
    awk -F'|' '{ k = $3 "|" ($4 + 0); if (!(k in n)) order[++m] = k; n[k]++
                 for (j = 10; j <= 13; j++) { v = $j + 0; if (!((k, j) in lo) || v < lo[k, j]) lo[k, j] = v; if (v > hi[k, j]) hi[k, j] = v }
                 if ($15 !~ /no/) ok[k]++ }
         END { for (i = 1; i <= m; i++) { k = order[i]; split(k, a, "|")
                   printf "|%s| %d |", a[1], a[2]
                   for (j = 10; j <= 13; j++) printf " %.2f-%.2fx |", lo[k, j], hi[k, j]
                   printf " %d of %d |\n", ok[k], n[k] } }' "$1"
}
rows="$work/rows.md"
awk -v work="$work/" '
    function field(line, k,   i, a, n) { n = split(line, a, " "); for (i = 2; i <= n; i++) if (index(a[i], k "=") == 1) return substr(a[i], length(k) + 2); return "" }
    FILENAME ~ /mem\.txt$/      { out[$1] = field($0, "out"); ar[$1] = field($0, "arena"); faces[$1] = field($0, "faces"); order[++n] = $1; next }
    FILENAME ~ /mem_lean\.txt$/ { lar[$1] = field($0, "arena"); next }
    FILENAME ~ /heap\.txt$/     { heap[$1] = field($0, "heap_peak"); next }
    FILENAME ~ /ir\.txt$/       { ir[$1] = $2; next }
    FILENAME ~ /ir_lean\.txt$/  { irl[$1] = $2; next }
    FILENAME ~ /ir_lib\.txt$/   { ird[$1] = $2; next }
    END {
        for (i = 1; i <= n; i++) {
            f = order[i]; name = f; sub(/.*\//, "", name); sub(/\.drc$/, "", name)
            split(name, p, "_"); k = p[length(p) - 2]; q = p[length(p) - 1]; cl = p[length(p)]
            mesh = name; sub("_" k "_" q "_" cl "$", "", mesh); sub(/^cl/, "", cl)
            kind = k == "n" ? "P+N" : k == "nt" ? "P+N+UV" : "P+C"
            qs = q == "q1" ? "11/10/8" : "14/12/10"
            r = ird[f] / ir[f]; rl = ird[f] / irl[f]; m = ar[f] / out[f]; ml = lar[f] / out[f]
            best = (r >= 2 && m <= 1.25) ? "default" : (rl >= 2 && ml <= 1.25) ? "lean" : "**no**"
            printf "| %s | %s | %s | %s | %d | %.2f | %.2f | %.2f | %.2fx | %.2fx | %.2fx | %.2fx | %.1f | %s |\n",
                mesh, kind, cl, qs, faces[f], ir[f] / 1e6, irl[f] / 1e6, ird[f] / 1e6, r, rl, m, ml,
                heap[f] / faces[f], best
        }
    }' "$work/mem.txt" "$work/mem_lean.txt" "$work/heap.txt" "$work/ir.txt" "$work/ir_lean.txt" \
       "$work/ir_lib.txt" > "$rows"

{
    echo "## Draco decoder on normals, texture coordinates and colours (issue 25)"
    echo
    echo "Command: \`make bench-draco\` (bench/draco_attrs.sh$( [ "$mode" = quick ] && echo ' quick')). The set: seven meshes"
    echo "that are not the dragons, made by \`gen-attr-meshes\` (tests/draco/gen_attr_meshes.cc):"
    echo "scanned-like closed surfaces of 20k and 82k faces (noise-displaced icospheres), a 121x121"
    echo "terrain (open), a CAD gear (fans, long thin faces, sharp edges), a torus with 40 holes,"
    echo "60 separate parts, and the npm bunny. Normals by assimp's aiProcess_GenSmoothNormals"
    echo "(80 degrees: the gear keeps split normals at its edges, attribute seams), texture"
    echo "coordinates by aiProcess_GenUVCoords (spherical, plane or cylindrical mapping), colours"
    echo "synthesised from the normal and the height. Encoded with \`draco_encoder -cl 4|7|10\` and"
    echo "quantization -qp/-qt/-qn 11/10/8 (the encoder's default) or 14/12/10. P+N: positions +"
    echo "normals, P+N+UV: + texture coordinates, P+C: positions + colours."
    echo
    echo "Instructions: callgrind inside the decode call (lumo_draco_decode_ex /"
    echo "draco::Decoder::DecodeMeshFromBuffer), both decoders producing the portable integers; one"
    echo "valgrind run per decoder over all streams, counts dumped per stream. Memory: lumo's exact"
    echo "arena (outputs + peak work) over its output, default and lean mode; libdraco's peak heap"
    echo "per face. \"both goals\": the mode reaching >= 2x fewer instructions and arena <= 1.25x."
    echo
    echo "| mesh | attributes | cl | qp/qt/qn | faces | lumo Minstr | lean Minstr | libdraco Minstr | instr ratio | lean instr ratio | arena/output | lean arena/output | libdraco heap B/face | both goals |"
    echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
    cat "$rows"
    echo
    echo "By attributes and level (rows of all meshes and both quantizations): the lowest and"
    echo "highest instruction ratio and arena/output of each mode, rows meeting both goals."
    echo
    echo "| attributes | cl | instr ratio | lean instr ratio | arena/output | lean arena/output | both goals |"
    echo "|---|---|---|---|---|---|---|"
    summary "$rows"
    echo
    awk -F'|' '{ n++; if ($15 ~ /no/) miss++; r = $10 + 0; rl = $11 + 0; if (!min || r < min) min = r; if (!minl || rl < minl) minl = rl }
         END { printf "Rows: %d; both goals met in one mode on %d; lowest instruction ratio %.2fx (default), %.2fx (lean).\n", n, n - miss, min, minl }' "$rows"
} > "$out"
echo "bench-draco-attrs: wrote $out"
