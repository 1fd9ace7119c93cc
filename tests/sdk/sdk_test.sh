#!/bin/sh
# tests/sdk/sdk_test.sh MAKE BUILD BIN PPM_PNG_SAME MODELS — the SDK as a
# user adopts it (docs/sdk.md): installed with `make install`, the example
# client built outside the tree with nothing but pkg-config, its pictures
# equal to lumo-render's. Prints "RESULT: N passed, M failed".
make=$1; build=$2; bin=$3; same=$4; models=$5
top=$(pwd)
dir="$top/$build/tests/sdk"
rm -rf "$dir" && mkdir -p "$dir/app"
pass=0; fail=0
ok()  { pass=$((pass + 1)); echo "ok   $1"; }
bad() { fail=$((fail + 1)); echo "FAIL $1"; }
check() { what=$1; shift; if "$@" >"$dir/last.log" 2>&1; then ok "$what"; else bad "$what"; sed 's/^/    /' "$dir/last.log" | tail -15; fi; }
finish() { echo "RESULT: $pass passed, $fail failed"; [ "$fail" -eq 0 ]; exit $?; }

version=$(sed -n 's/^#define LUMO_VERSION_\(MAJOR\|MINOR\|PATCH\) *\([0-9]*\).*/\2/p' sdk/include/lumo/version.h | paste -sd.)
files() { (cd "$1" && find . -type f | sort); }

# ---- install into a prefix, use it through pkg-config ---------------------------
pfx="$dir/prefix"
check "make install PREFIX=$pfx" $make --no-print-directory -s install PREFIX="$pfx" BUILD="$build"
export PKG_CONFIG_PATH="$pfx/lib/pkgconfig" PKG_CONFIG_LIBDIR="$pfx/lib/pkgconfig"
for pc in lumo lumo-raster lumo-net; do
    check "pkg-config $pc: valid, version $version" \
        sh -c "pkg-config --validate $pc && test \"\$(pkg-config --modversion $pc)\" = $version"
done
check "pkg-config lumo-raster: its flags point into the prefix only" \
    sh -c "test \"\$(echo \$(pkg-config --cflags --libs lumo-raster))\" = \"-I$pfx/include -L$pfx/lib -llumo_raster -llumo\""

# The example, copied out of the tree so only the installed headers can be found.
cp sdk/examples/lumo_view.c "$dir/app/"
check "example builds against the installed SDK (C99, -Werror, ASan/UBSan)" \
    sh -c "cd '$dir/app' && cc -std=c99 -pedantic -Wall -Wextra -Werror -g -fsanitize=address,undefined \
           -fno-sanitize-recover=all lumo_view.c \$(pkg-config --cflags --libs lumo-raster) -o lumo_view"
view="$dir/app/lumo_view"
[ -x "$view" ] || finish

# ---- its pictures equal lumo-render's -----------------------------------------
dragon=$models/dragon_11k.ply
if [ -f "$dragon" ]; then
    check "lumo-bake: a dragon scene with progressive meshes and an IVG" \
        timeout 120 "$bin/lumo-bake" --default --dragon "$dragon" --grid 8 --spp 4 --no-progress -o "$dir/dragon.lumo"
else
    bad "$dragon missing: run tools/setup.sh"
fi
seeds=tests/fuzz/seeds/fuzz_package
for pkg in "$dir/dragon.lumo" $seeds/example.lumo $seeds/stream.lumo $seeds/lights.lumo; do
    [ -f "$pkg" ] || continue
    name=$(basename "$pkg" .lumo)
    for size in 320x240 97x61; do
        check "$name $size: lumo_view runs" "$view" "$pkg" "$dir/$name-$size.ppm" "$size"
        check "$name $size: lumo-render draws it" "$bin/lumo-render" "$pkg" -o "$dir/$name-$size.png" --size "$size"
        check "$name $size: lumo_view's frame == lumo-render's, byte for byte" \
            "$same" "$dir/$name-$size.ppm" "$dir/$name-$size.png"
    done
done
# The comparison itself can fail: a frame of another package differs.
if [ -f "$dir/dragon-320x240.ppm" ] && [ -f "$dir/example-320x240.png" ]; then
    check "the comparison sees a different frame" sh -c "! '$same' '$dir/dragon-320x240.ppm' '$dir/example-320x240.png'"
fi

# ---- hostile input: one line, exit 1, no sanitizer report ----------------------
refused() {  # refused NAME FILE: lumo_view exits 1 with one error line
    "$view" "$2" "$dir/refused.ppm" >"$dir/refused.out" 2>"$dir/refused.err"; st=$?
    if [ $st -eq 1 ] && [ "$(wc -l <"$dir/refused.err")" -eq 1 ] && grep -q '^lumo_view: error: ' "$dir/refused.err"; then
        ok "$1 refused: $(cat "$dir/refused.err")"
    else
        bad "$1: exit $st"; sed 's/^/    /' "$dir/refused.err" | head -10
    fi
}
src=$seeds/stream.lumo
size=$(wc -c <"$src")
head -c $((size / 2)) "$src" >"$dir/cut.lumo";            refused "a package cut in half" "$dir/cut.lumo"
cp "$src" "$dir/flip.lumo"
printf '\377' | dd of="$dir/flip.lumo" bs=1 seek=$((size - 9)) conv=notrunc 2>/dev/null
refused "a package with a flipped byte" "$dir/flip.lumo"
refused "a missing file" "$dir/no-such.lumo"
: >"$dir/empty.lumo";                                      refused "an empty file" "$dir/empty.lumo"
refused "a version-1 package" tests/server/data/v1_tiny.lumo

# ---- uninstall, DESTDIR, bare metal ---------------------------------------------
check "make uninstall leaves the prefix empty of files" \
    sh -c "$make --no-print-directory -s uninstall PREFIX='$pfx' BUILD='$build' && test -z \"\$(find '$pfx' -type f)\""
stage="$dir/stage"
check "make install PREFIX=/usr DESTDIR=stage" \
    $make --no-print-directory -s install PREFIX=/usr DESTDIR="$stage" BUILD="$build"
check "DESTDIR: the .pc files name /usr, not the staging directory" \
    sh -c "grep -qx 'prefix=/usr' '$stage/usr/lib/pkgconfig/lumo.pc' && ! grep -rq '$stage' '$stage/usr/lib/pkgconfig'"
check "DESTDIR: through a sysroot, pkg-config finds the staged headers" \
    sh -c "test \"\$(echo \$(PKG_CONFIG_SYSROOT_DIR='$stage' PKG_CONFIG_LIBDIR='$stage/usr/lib/pkgconfig' \
           pkg-config --cflags lumo))\" = '-I$stage/usr/include'"
check "make uninstall DESTDIR=stage leaves no file" \
    sh -c "$make --no-print-directory -s uninstall PREFIX=/usr DESTDIR='$stage' BUILD='$build' && test -z \"\$(find '$stage' -type f)\""
fw="$dir/firmware"
check "make install CROSS=arm-none-eabi- CPU=cortex-m4: Arm objects" \
    sh -c "$make --no-print-directory -s install CROSS=arm-none-eabi- CPU=cortex-m4 PREFIX='$fw' BUILD='$build' >/dev/null \
           && arm-none-eabi-objdump -f '$fw/lib/liblumo.a' | grep -q 'file format elf32-littlearm' \
           && arm-none-eabi-objdump -f '$fw/lib/liblumo_raster.a' | grep -q 'file format elf32-littlearm'"

# ---- the tools say which lumo they are -------------------------------------------
for t in lumo-bake lumo-server lumo-client lumo-render; do
    check "$t --version: lumo $version and the format versions" \
        sh -c "'$bin/$t' --version | grep -qx '$t lumo $version (package format [0-9]*\.[0-9]*, progressive mesh [0-9]*, IVG bundle [0-9]*, protocol [0-9]*)'"
done

# ---- the CHANGELOG is at the headers' version ------------------------------------
check "CHANGELOG.md's newest release is $version" \
    sh -c "grep -m1 '^## [0-9]' CHANGELOG.md | grep -q '^## $version '"
finish
