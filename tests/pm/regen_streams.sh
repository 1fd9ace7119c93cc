#!/bin/sh
# tests/pm/regen_streams.sh [BUILD] — rewrite every stored progressive-mesh
# stream after a change of the stream format or of what the server writes
# (the simplifier, the stream writer): the fuzz_pmesh seeds, the unit
# streams of tests/unit/test_pmesh.c (tiny_coded.lpm's and tiny_seeded.lpm's bytes), the
# fuzz_package packages (tests/fuzz/package_seeds/make.sh) and the worked
# example of docs/protocol.md §6. Run from the top of the tree, then
# `make test` and commit the result.
set -e
build=${1:-build}
make -j2 "$build/tests/bin/pm_check" "$build/bin/lumo-bake" "$build/bin/prt-demo" \
    "$build/tests/bin/test_protocol_example" >/dev/null
check=$build/tests/bin/pm_check
seeds=tests/fuzz/seeds/fuzz_pmesh
"$check" --gen tiny --batch 3 --max-error 0 --write-stream "$seeds/tiny_coded.lpm"
"$check" --gen tiny --batch 3 --max-error 0.15 --write-stream "$seeds/tiny_seeded.lpm"
"$check" --gen tiny --batch 3 --max-error 0 --predicted --write-stream "$seeds/tiny_predicted.lpm"
"$check" --gen tiny --batch 3 --max-error 0 --absolute --write-stream "$seeds/tiny_absolute.lpm"
"$check" --gen grid --batch 40 --max-error 0 --write-stream "$seeds/grid.lpm"
"$check" --gen seam --batch 7 --albedo --max-error 0 --write-stream "$seeds/seam_albedo.lpm"
"$check" --gen voxel --batch 50 --lattice on --write-stream "$seeds/voxel_lattice.lpm"
# test_pmesh.c's k_stream and k_seeded: the bytes of tiny_coded.lpm and
# tiny_seeded.lpm (a base record with splits from its seed), 16 a line
python3 - tests/unit/test_pmesh.c "$seeds/tiny_coded.lpm" k_stream "$seeds/tiny_seeded.lpm" k_seeded <<'PY'
import sys
src = open(sys.argv[1]).read()
for path, name in zip(sys.argv[2::2], sys.argv[3::2]):
    data = open(path, 'rb').read()
    lines = ['    ' + ', '.join('0x%02x' % b for b in data[i:i + 16]) + ',' for i in range(0, len(data), 16)]
    head = 'static const uint8_t %s[] = {\n' % name
    a = src.index(head) + len(head)
    b = src.index('};', a)
    src = src[:a] + '\n'.join(lines) + '\n' + src[b:]
open(sys.argv[1], 'w').write(src)
PY
sh tests/fuzz/package_seeds/make.sh "$build/bin" >/dev/null 2>&1
# docs/protocol.md §6 from the regenerated example.lumo
"$build/tests/bin/test_protocol_example" --markdown >"$build/protocol-6.md"
python3 - docs/protocol.md "$build/protocol-6.md" <<'PY'
import re, sys
doc = open(sys.argv[1]).read()
m = re.search(r'^## 6\..*\n', doc, re.M)
end = doc.index('\n## 7.', m.end())
open(sys.argv[1], 'w').write(doc[:m.end()] + open(sys.argv[2]).read() + doc[end + 1:])
PY
echo "regenerated: $seeds/*.lpm, tests/unit/test_pmesh.c k_stream and k_seeded, tests/fuzz/seeds/fuzz_package/*.lumo, docs/protocol.md §6"
