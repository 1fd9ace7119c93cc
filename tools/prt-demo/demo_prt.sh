#!/bin/sh
# tools/prt-demo/demo_prt.sh BIN OUT MODEL — make demo-prt (prt-demo.mk).
set -e
bin=$1; out=$2; model=$3
mkdir -p "$out"
size=${SIZE:-320x240}
prt=${PRT:-6,strata=24,bounces=1,components=8}
"$bin/prt-demo" env "$out/sky.png" 256 128
bake() {   # NAME SPEC
    "$bin/lumo-bake" "$model" --light directional:0,-1,0:1,1,1 --grid 4 --spp 4 --no-progress \
        --prt "$prt,$2" --prt-env "$out/sky.png" -o "$out/$1.lumo" 2>&1 | tail -n 1
}
bake full clusters=1,components=36
bake cpca clusters=64,registers=0
bake coherent clusters=64,alpha=2,registers=0
bake super clusters=64,registers=256
render() {   # PACKAGE OUT [ARGS]
    p=$1; o=$2; shift 2
    "$bin/lumo-render" "$out/$p.lumo" --prt --size "$size" --exposure "${EXPOSURE:-3}" -o "$out/$o.png" "$@" | tail -n 1
}
render full full
render cpca cpca
render coherent coherent
render super super
render cpca clusters_cpca --prt-view clusters
render coherent clusters_coherent --prt-view clusters
render super passes_super --prt-view passes
render cpca turn --frames 4 --rotate 90
echo "demo-prt: uncompressed vs CPCA vs geometry coherence vs super-clusters (errors against the first):"
"$bin/lumo-compare" "$out/full.png" "$out/cpca.png" "$out/coherent.png" "$out/super.png" \
    --labels "UNCOMPRESSED,CPCA 64,COHERENCE A=2,SUPER-CLUSTERS" -o "$out/row_lit.png"
"$bin/lumo-compare" "$out/clusters_cpca.png" "$out/clusters_coherent.png" "$out/passes_super.png" \
    --labels "CLUSTERS CPCA,CLUSTERS COHERENCE,PASSES SUPER" -o "$out/row_clusters.png" >/dev/null
"$bin/lumo-compare" "$out/turn_000.png" "$out/turn_001.png" "$out/turn_002.png" "$out/turn_003.png" \
    --labels "SKY 0,SKY 90,SKY 180,SKY 270" -o "$out/row_turn.png" >/dev/null
"$bin/prt-demo" stack "$out/contact.png" "$out/row_lit.png" "$out/row_clusters.png" "$out/row_turn.png"
echo "demo-prt: contact sheet $out/contact.png"
