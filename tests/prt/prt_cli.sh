#!/bin/sh
# tests/prt/prt_cli.sh BIN WORKDIR — PRT from the outside (docs/prt.md):
# lumo-bake --prt writes a PRTV chunk after the PMSH (and PRTL with
# --prt-env), the same seed gives the same bytes, bad --prt values are one
# error line; lumo-render --prt relights (a turning sky changes the frames,
# a full turn brings the first back), --prt-view draws, and a package
# without PRT is refused. Prints "RESULT: N passed, M failed".
bin=$1; dir=$2
mkdir -p "$dir"
pass=0; fail=0
ok()  { pass=$((pass + 1)); echo "ok   $1"; }
bad() { fail=$((fail + 1)); echo "FAIL $1"; }
expect_error() {
    name=$1; shift
    "$@" >"$dir/out" 2>"$dir/err"; st=$?
    if [ $st -ne 0 ] && grep -q -e "error" -e "^usage:" "$dir/err"; then ok "$name: $(grep -m 1 -e error -e usage "$dir/err")"
    else bad "$name (status $st)"; sed 's/^/    /' "$dir/err"; fi
}

# A box on a floor (the floor shadows nothing, the box shadows the floor).
cat >"$dir/scene.obj" <<'OBJ'
v -1 0 -1
v 1 0 -1
v 1 0 1
v -1 0 1
v -0.3 0 -0.3
v 0.3 0 -0.3
v 0.3 0 0.3
v -0.3 0 0.3
v -0.3 0.6 -0.3
v 0.3 0.6 -0.3
v 0.3 0.6 0.3
v -0.3 0.6 0.3
f 1 3 2
f 1 4 3
f 9 11 10
f 9 12 11
f 5 6 10
f 5 10 9
f 6 7 11
f 6 11 10
f 7 8 12
f 7 12 11
f 8 5 9
f 8 9 12
OBJ
bake="$bin/lumo-bake $dir/scene.obj --light directional:0.3,-1,0.2:2,2,2 --grid 3 --spp 2 --threads 2 --no-progress"
"$bin/prt-demo" env "$dir/sky.png" 64 32 || bad "prt-demo env"
if $bake --prt 4,clusters=3,components=4,strata=8 --prt-env "$dir/sky.png" -o "$dir/a.lumo" 2>"$dir/err"; then
    "$bin/lumo-inspect" "$dir/a.lumo" >"$dir/list"
    grep -q "PMSH" "$dir/list" && grep -q "PRTV" "$dir/list" && grep -q "PRTL" "$dir/list" \
        && [ "$(grep -n PRTV "$dir/list" | cut -d: -f1)" -gt "$(grep -n PMSH "$dir/list" | cut -d: -f1)" ] \
        && ok "lumo-bake --prt: PRTV after PMSH, PRTL" || { bad "chunk list"; cat "$dir/list"; }
else bad "lumo-bake --prt"; cat "$dir/err"; fi
$bake --prt 4,clusters=3,components=4,strata=8 --prt-env "$dir/sky.png" -o "$dir/b.lumo" 2>/dev/null
cmp -s "$dir/a.lumo" "$dir/b.lumo" && ok "same seed, same bytes" || bad "same seed, same bytes"
$bake -o "$dir/plain.lumo" 2>/dev/null || bad "plain bake"

expect_error "--prt 9" $bake --prt 9 -o "$dir/x.lumo"
expect_error "--prt 4,clusters=0" $bake --prt 4,clusters=0 -o "$dir/x.lumo"
expect_error "--prt 4,teapot=1" $bake --prt 4,teapot=1 -o "$dir/x.lumo"
expect_error "--prt-env without --prt" $bake --prt-env "$dir/sky.png" -o "$dir/x.lumo"
expect_error "--prt-env missing file" $bake --prt 4 --prt-env "$dir/none.png" -o "$dir/x.lumo"

render="$bin/lumo-render --size 96x72"
if $render "$dir/a.lumo" --prt --frames 5 --rotate 90 -o "$dir/t.png" >"$dir/out" 2>"$dir/err"; then
    grep -q "PRT order 4" "$dir/out" && ok "lumo-render --prt: $(grep PRT "$dir/out")" || bad "no PRT line"
    cmp -s "$dir/t_000.png" "$dir/t_001.png" && bad "a turned sky changes nothing" || ok "a turned sky changes the frame"
    cmp -s "$dir/t_000.png" "$dir/t_004.png" && ok "a full turn gives the first frame back" \
        || bad "a full turn differs"
else bad "lumo-render --prt"; cat "$dir/err"; fi
$render "$dir/a.lumo" --prt --env "$dir/sky.png" -o "$dir/e.png" >/dev/null 2>&1 && ok "--env" || bad "--env"
$render "$dir/a.lumo" --prt --prt-view passes -o "$dir/p.png" >/dev/null 2>&1 && ok "--prt-view passes" \
    || bad "--prt-view"
expect_error "package without PRT" $render "$dir/plain.lumo" --prt -o "$dir/x.png"
expect_error "--prt-view on the GL backend" $render "$dir/a.lumo" --prt --prt-view clusters --backend osmesa -o "$dir/x.png"
expect_error "--rotate without --prt" $render "$dir/a.lumo" --rotate 10 -o "$dir/x.png"
echo "RESULT: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
