#!/bin/sh
# tests/board/check_embedded_selftest.sh DIR "CC CFLAGS" NM CHECK_SCRIPT
#
# Proves that check-embedded can fail: writes small C files into DIR (under
# build/, never client code), compiles each with the Cortex-M3 client flags
# and runs the check on it alone. Every bad case must make the check fail
# with a message naming the file and the offending symbol or word; the good
# case (integer code, "double" only in a comment and a string) must pass.
# Prints "RESULT: N passed, M failed".
dir=$1; cc=$2; nm=$3; check=$4
mkdir -p "$dir"
pass=0; fail=0

# case NAME EXPECT(pass|fail) MESSAGE-REGEX  (source on stdin)
case_() {
    name=$1; expect=$2; want=$3
    cat >"$dir/$name.c"
    if ! $cc -c "$dir/$name.c" -o "$dir/$name.o" 2>"$dir/$name.cc.log"; then
        echo "FAIL $name: does not compile (see $dir/$name.cc.log)"; fail=$((fail + 1)); return
    fi
    out=$(sh "$check" "$nm" "$dir/$name.o" "$dir/$name.c" 2>&1); rc=$?
    echo "$out" >"$dir/$name.log"
    if [ "$expect" = pass ] && [ "$rc" -eq 0 ]; then
        echo "ok   $name: accepted"; pass=$((pass + 1))
    elif [ "$expect" = fail ] && [ "$rc" -ne 0 ] && echo "$out" | grep -Eq "FAIL [^ ]*$name\.[co]: .*$want"; then
        echo "ok   $name: rejected — $(echo "$out" | grep 'FAIL' | head -n 1)"; pass=$((pass + 1))
    else
        echo "FAIL $name: expected $expect matching '$want', check exited $rc:"
        echo "$out" | grep -v '^RESULT' | sed 's/^/    /'; fail=$((fail + 1))
    fi
}

case_ good pass '' <<'C'
/* A double in a comment is fine: double d = 0.5; */
#include <stdint.h>
#include <string.h>
int32_t good_mul(int32_t a, int32_t b);
const char *good_name(void);
int32_t good_mul(int32_t a, int32_t b) { int32_t t; memcpy(&t, &a, sizeof t); return (int32_t)(((int64_t)t * b) >> 16); }
const char *good_name(void) { return "float and double 1.5 in a string"; }
C

case_ heap fail 'heap symbol malloc' <<'C'
#include <stddef.h>
void *malloc(size_t n);
void *heap_get(size_t n);
void *heap_get(size_t n) { return malloc(n); }
C

case_ sbrk fail 'heap symbol _sbrk' <<'C'
void *_sbrk(int incr);
void *sbrk_get(void);
void *sbrk_get(void) { return _sbrk(64); }
C

case_ floatmul fail 'soft-float helper __aeabi_f' <<'C'
#include <stdint.h>
int32_t scale(int32_t v, float k);
int32_t scale(int32_t v, float k) { return (int32_t)((float)v * k); }
C

case_ doubleadd fail 'soft-float helper __aeabi_d' <<'C'
#include <stdint.h>
int64_t twice(int64_t v);
int64_t twice(int64_t v) { volatile double d = (double)v; return (int64_t)(d + d); }
C

case_ printf fail 'external symbol printf' <<'C'
int printf(const char *fmt, ...);
void say(int v);
void say(int v) { printf("%d", v); }
C

# No symbol betrays these: only the source check can catch them.
case_ srcdouble fail 'float/double in code' <<'C'
typedef double unused_real;
int src_double(void);
int src_double(void) { return (int)sizeof(unused_real); }
C

case_ srcliteral fail 'floating-point literal' <<'C'
int src_literal(void);
int src_literal(void) { return (int)(0.5 * 4); }
C

case_ srcheader fail 'system header other than' <<'C'
#include <stdlib.h>
int src_header(void);
int src_header(void) { return EXIT_SUCCESS; }
C

echo "RESULT: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
