#!/bin/sh
# boards/armv7m/check-embedded.sh — prove the client rules (ARCHITECTURE.md
# "Rules for the client side") on the Cortex-M3 objects and on the sources.
#
#   check-embedded.sh NM "OBJECTS" "SOURCES"
#
# NM       arm-none-eabi-nm (or any nm that reads the objects)
# OBJECTS  client objects built with -mfloat-abi=soft (build/m3/...)
# SOURCES  client .c/.h files to scan for float/double and foreign headers
#
# Three rules, each failure printed as "check-embedded: FAIL <where>: <why>":
#  1. no object references or defines a heap symbol (malloc, free, _sbrk, ...);
#  2. no object references a soft-float helper (__aeabi_f*, __aeabi_d*, the
#     libgcc __addsf3 family, libm maths): with -mfloat-abi=soft any float
#     arithmetic that survives compilation shows up as one of these;
#  3. every other undefined symbol is defined by another client object or is
#     on a short allow-list (string.h and libgcc's integer helpers, and the
#     linker-script symbols of the ARMv7-M family code, docs/porting.md §6),
#     so stdio, assert, abort and friends cannot sneak in (they pull the heap
#     on newlib);
#  4. no source mentions float/double or a floating literal outside comments,
#     and includes only <stdint.h>, <stddef.h>, <string.h> among system headers.
# Exit status 0 when clean, 1 otherwise. Prints "RESULT: N passed, M failed"
# (one test per object and per source file) so tests/run.sh can count it.
set -u
NM=$1; OBJS=$2; SRCS=$3

HEAP_RE='^(malloc|calloc|realloc|reallocf|free|cfree|valloc|pvalloc|memalign|aligned_alloc|posix_memalign|sbrk|_sbrk|_sbrk_r|brk|_malloc_r|_calloc_r|_realloc_r|_free_r|_memalign_r|__malloc_lock|__malloc_unlock|_malloc_usable_size_r|malloc_usable_size|strdup|strndup|_strdup_r|_strndup_r|__builtin_malloc|mmap|munmap)$'
FLOAT_RE='^(__aeabi_[fd].*|__aeabi_u?[il]2[fd]|__aeabi_c[fd].*|__(add|sub|mul|div|neg|extend|trunc|float|fix|cmp|eq|ne|lt|le|gt|ge|unord|pow)[a-z]*[sdxt]f[0-9]*|(sqrt|cbrt|exp|exp2|expm1|log|log2|log10|log1p|pow|sin|cos|tan|asin|acos|atan|atan2|sinh|cosh|tanh|floor|ceil|round|lround|trunc|fabs|fmod|fmin|fmax|frexp|ldexp|modf|hypot|nearbyint|rint|lrint)[fl]?)$'
# string.h, the integer helpers libgcc provides for 64-bit and division (and
# the Thumb-1 switch tables of ARMv6-M, boards/rp2040), and
# the symbols a board's linker script defines for startup.c and fault.c.
ALLOW_RE='^(__(data_load|data_start|data_end|bss_start|bss_end|stack_top|stack_paint_low)|mem(cpy|move|set|cmp|chr)|str(len|nlen|cmp|ncmp|chr|rchr|cpy|ncpy|cat|ncat|spn|cspn|pbrk|str)|__aeabi_(u?ldivmod|u?idiv|u?idivmod|llsl|llsr|lasr|lmul|u?lcmp|mem(cpy|move|set|clr)[48]?)|__(u?divdi3|u?moddi3|udivmoddi4|muldi3|ashldi3|lshrdi3|ashrdi3|u?cmpdi2|(clz|ctz|ffs|popcount|parity|bswap)[sd]i2)|__gnu_thumb1_case_(uqi|sqi|uhi|shi|si))$'

pass=0; fail=0
report() { echo "check-embedded: FAIL $1: $2"; }

# Every symbol some client object defines: references to them are internal.
defined=$(for o in $OBJS; do "$NM" -g --defined-only "$o" 2>/dev/null; done | awk 'NF >= 3 {print $3}' | sort -u)

check_object() {  # check_object OBJ -> 0 clean, 1 dirty
    o=$1; bad=0
    if [ ! -f "$o" ]; then report "$o" "object missing (build it first)"; return 1; fi
    syms=$("$NM" -g "$o") || { report "$o" "nm could not read it"; return 1; }
    # defined heap symbols are as bad as references (a private malloc is a heap)
    for s in $(echo "$syms" | awk '{print $NF}' | grep -E "$HEAP_RE"); do
        report "$o" "heap symbol $s"; bad=1
    done
    for s in $(echo "$syms" | awk '$1 == "U" {print $2}'); do
        if echo "$s" | grep -Eq "$HEAP_RE"; then continue; fi
        if echo "$s" | grep -Eq "$FLOAT_RE"; then
            report "$o" "soft-float helper $s (float/double arithmetic on the client)"; bad=1
        elif ! echo "$s" | grep -Eq "$ALLOW_RE" && ! echo "$defined" | grep -qx "$s"; then
            report "$o" "external symbol $s is not allowed on the client (only string.h and integer libgcc helpers)"; bad=1
        fi
    done
    return $bad
}

# Comments and string/char literals removed, so only code is scanned.
strip_code() {
    sed -e 's/\\\\//g' "$1" | awk '
    { line = $0; out = ""; i = 1; n = length(line)
      while (i <= n) {
        c = substr(line, i, 1); d = substr(line, i, 2)
        if (inc) { if (d == "*/") { inc = 0; i += 2; out = out " " } else i++; continue }
        if (d == "/*") { inc = 1; i += 2; continue }
        if (d == "//") break
        if (c == "\"" || c == "'\''") {
          q = c; i++
          while (i <= n && substr(line, i, 1) != q) { if (substr(line, i, 1) == "\\") i++; i++ }
          i++; out = out q q; continue
        }
        out = out c; i++
      }
      print out }'
}

check_source() {  # check_source FILE -> 0 clean, 1 dirty
    f=$1; bad=0
    if [ ! -f "$f" ]; then report "$f" "source missing"; return 1; fi
    code=$(strip_code "$f")
    hits=$(echo "$code" | grep -nwE 'float|double|_Complex|float_t|double_t' | head -3)
    if [ -n "$hits" ]; then
        report "$f" "float/double in code: $(echo "$hits" | tr '\n' ' ')"; bad=1
    fi
    hits=$(echo "$code" | grep -nE '(^|[^0-9A-Za-z_.])([0-9]+\.[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?[fFlL]?([^0-9A-Za-z_]|$)|(^|[^0-9A-Za-z_.])[0-9]+[eE][-+]?[0-9]+' | grep -v '^[0-9]*: *#' | head -3)
    if [ -n "$hits" ]; then
        report "$f" "floating-point literal: $(echo "$hits" | tr '\n' ' ')"; bad=1
    fi
    hits=$(echo "$code" | grep -nE '^[[:space:]]*#[[:space:]]*include[[:space:]]*<' \
           | grep -vE '<(stdint|stddef|string)\.h>' | head -3)
    if [ -n "$hits" ]; then
        report "$f" "system header other than stdint.h/stddef.h/string.h: $(echo "$hits" | tr '\n' ' ')"; bad=1
    fi
    return $bad
}

for o in $OBJS; do
    if check_object "$o"; then pass=$((pass + 1)); else fail=$((fail + 1)); fi
done
for f in $SRCS; do
    if check_source "$f"; then pass=$((pass + 1)); else fail=$((fail + 1)); fi
done
echo "check-embedded: $(echo $OBJS | wc -w) objects, $(echo $SRCS | wc -w) sources checked"
echo "RESULT: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
