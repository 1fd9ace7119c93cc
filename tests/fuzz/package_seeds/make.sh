#!/bin/sh
# tests/fuzz/package_seeds/make.sh BIN — regenerate the real packages among
# the fuzz_package seeds with BIN/lumo-bake (run it from the top of the
# tree after a change of the package format, and commit the result):
#   tiny.lumo    raw MESH chunks, a 3x3x3 IVG
#   lights.lumo  raw MESH chunks, every light kind, a 2x3x2 IVG
#   stream.lumo  progressive PMSH streams, a 4x3x4 IVG, IVGS and ORDR
#   prt.lumo     stream.lumo with PRT (PRTV, PRTL)
#   example.lumo one quad, a 3x2x2 IVG: docs/protocol.md §6, checked by
#                tests/serve/test_protocol_example.c (regenerate §6 with it)
set -e
bin=${1:-build/bin}
src=tests/fuzz/package_seeds
out=tests/fuzz/seeds/fuzz_package
"$bin/lumo-bake" "$src/tiny.txt" --mesh raw --grid 3 --spp 4 --threads 1 --no-progress -o "$out/tiny.lumo"
"$bin/lumo-bake" "$src/lights.txt" --mesh raw --grid 2,3,2 --spp 2 --threads 1 --no-progress -o "$out/lights.lumo"
"$bin/lumo-bake" "$src/stream.txt" --grid 4,3,4 --spp 2 --threads 1 --no-progress -o "$out/stream.lumo"
"$bin/lumo-bake" "$src/example.txt" --grid 3,2,2 --spp 1 --seed 1 --threads 1 --no-progress -o "$out/example.lumo"
# prt.lumo: the stream.lumo scene with PRT (order 3, 6 clusters, 3
# components; PRTV per mesh, PRTL of prt-demo's sky): tests/prt/test_prt_session.c
sky=$(mktemp --suffix .png)
"$bin/prt-demo" env "$sky" 32 16
"$bin/lumo-bake" "$src/stream.txt" --grid 2 --spp 1 --threads 1 --no-progress \
    --prt 3,clusters=6,components=3,strata=6 --prt-env "$sky" -o "$out/prt.lumo"
rm -f "$sky"
