#!/bin/sh
# tests/sdk/docs_check.sh WORKDIR VERSION — the API reference builds from the
# installed headers without one warning (no undocumented public symbol), and
# the check can fail: a header with an undocumented function, field or macro
# is refused by name; a plain comment above a declaration documents it.
# Prints "RESULT: N passed, M failed".
dir=$1; version=$2
rm -rf "$dir" && mkdir -p "$dir/out" "$dir/self"
pass=0; fail=0
ok()  { pass=$((pass + 1)); echo "ok   $1"; }
bad() { fail=$((fail + 1)); echo "FAIL $1"; }

# doxy INPUT OUT: Doxygen with the project's configuration on INPUT.
doxy() {
    { cat sdk/docs/Doxyfile; [ -n "$1" ] && echo "INPUT = $1"; echo "OUTPUT_DIRECTORY = $2"; } \
        | LUMO_DOC_VERSION=$version doxygen - >"$2.log" 2>&1
}

if doxy "" "$dir/out" && ! grep -q . "$dir/out.log"; then
    ok "API reference of the public headers: no warning"
else
    bad "API reference of the public headers: $(grep -c . "$dir/out.log") warnings"
    head -40 "$dir/out.log" | sed 's/^/    /'
fi

cat >"$dir/self/good.h" <<'H'
/*
 * good.h — a header documented in the headers' plain style.
 */
#define GOOD_LIMIT 4u   /* a macro's trailing comment */

/* A type; its fields documented after them. */
typedef struct good_pair {
    int a, b;   /* both named by one comment */
} good_pair;

/* A function documented by the comment right above it. */
int good_sum(const good_pair *p);
H
if doxy "$dir/self/good.h" "$dir/self/good" && ! grep -q . "$dir/self/good.log"; then
    ok "plain comments above and after declarations document them"
else
    bad "plain comments above and after declarations document them"; sed 's/^/    /' "$dir/self/good.log" | head
fi

cp "$dir/self/good.h" "$dir/self/bad.h"
cat >>"$dir/self/bad.h" <<'H'

/* ---- a section rule documents nothing ---- */

int bad_undocumented(void);
typedef struct bad_fields {
    int documented;   /* yes */
    int forgotten;
} bad_fields;

/* Followed by a blank line: not the documentation of what comes next. */

#define BAD_MACRO 1
H
doxy "$dir/self/bad.h" "$dir/self/bad"; st=$?
for name in bad_undocumented forgotten BAD_MACRO; do
    if [ $st -ne 0 ] && grep -q "$name.*is not documented" "$dir/self/bad.log"; then
        ok "an undocumented $name fails the check"
    else
        bad "an undocumented $name fails the check (exit $st)"; sed 's/^/    /' "$dir/self/bad.log" | head
    fi
done
echo "RESULT: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
