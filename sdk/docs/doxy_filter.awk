# sdk/docs/doxy_filter.awk — Doxygen's INPUT_FILTER for the public headers
# (sdk/docs/Doxyfile). The headers keep plain C comments; the rule that makes
# a comment documentation is the one a reader already follows:
#   - the file's first comment documents the file (@file);
#   - a comment on its own lines directly above a declaration (no blank line
#     between) documents that declaration;
#   - a comment after code on the same line documents that member, enum
#     value or macro;
#   - everything else stays a plain comment: one-line section rules
#     (/* ---- x ---- */),
#     comments followed by a blank line, and every comment inside a function
#     body (static inline helpers);
#   - a comment right above several declarations in a row (up to a blank
#     line or the next comment: `lumo_x_encode` and `lumo_x_decode` under
#     one comment) documents each of them (a member group, its doc
#     distributed: DISTRIBUTE_GROUP_DOC);
#   - a field line declaring several names (`uint32_t a, b;  /* x */`) is
#     split into one declaration per name on the same line, each with the
#     comment, so every name is documented;
#   - a struct whose comment says "Fields are private" gets @privatesection:
#     its fields are the SDK's, not part of the documented API.
# Only comment openers are rewritten; line numbers are kept, so Doxygen's
# warnings point at the real lines.
{ line[NR] = $0 }
END {
    depth = 0; body = 0; incomment = 0; first = 1
    for (i = 1; i <= NR; i++) {
        s = line[i]
        if (!incomment && depth > 0 && !body) s = split_fields(s)
        if (!incomment) s = open_comment(s, i)
        if (i in group_open) s = s " /**@{*/"
        if (i in group_close) s = "/**@}*/ " s
        if (depth == 0 && line[i] ~ /[Ff]ields are private/) private = 1
        if (depth == 0 && private && line[i] ~ /(struct|union)[^;]*\{/) { s = s " /** @privatesection */"; private = 0 }
        if (depth == 0 && !incomment && line[i] !~ /^[ \t]*(\/\*|\*)/ && line[i] ~ /;/) private = 0
        print s
        track(line[i])
    }
}

# Rewrite the opener of a comment starting on line i (outside a comment).
function open_comment(s, i,    p, before, text) {
    p = index(s, "/*")
    if (p == 0) return s
    before = substr(s, 1, p - 1)
    if (index(before, "//") || quote_count(before) % 2) return s
    text = substr(s, p)
    if (substr(text, 1, 3) == "/**" || substr(text, 1, 3) == "/*!" || body) return s
    if (first && before ~ /^[ \t]*$/) {
        first = 0
        return before "/** @file" substr(text, 3)
    }
    first = 0
    if (before !~ /^[ \t]*$/)
        return before "/**<" substr(text, 3)
    if ((text ~ /^\/\*[ \t]*-/ && text ~ /\*\/[ \t]*$/) || !touches_code(i)) return s
    if (depth == 0) group_after(i)
    return before "/**" substr(text, 3)
}

# `TYPE a, *b[3];  /* doc */` -> `TYPE a; /**< doc */ TYPE *b[3]; /**< doc */`
# for a one-line doc comment or none; other lines come back unchanged.
function split_fields(s,    p, code, com, first, type, n, k, d, out, doc) {
    p = index(s, "/*")
    code = p ? substr(s, 1, p - 1) : s
    com = p ? substr(s, p) : ""
    if (com != "" && (com !~ /\*\/[ \t]*$/ || substr(com, 1, 3) == "/**")) return s
    if (code !~ /^[ \t]*[A-Za-z_][A-Za-z_0-9 ]*[ \t*][ \t*]*[A-Za-z_][A-Za-z_0-9]*(\[[^]]*\])*[ \t]*(,[ \t]*\**[ \t]*[A-Za-z_][A-Za-z_0-9]*(\[[^]]*\])*[ \t]*)+;[ \t]*$/)
        return s
    doc = com == "" ? "" : " /**<" substr(com, 3)
    first = substr(code, 1, index(code, ",") - 1)
    type = first
    sub(/\**[ \t]*[A-Za-z_][A-Za-z_0-9]*(\[[^]]*\])*[ \t]*$/, "", type)
    d = substr(first, length(type) + 1)
    sub(/[ \t]+$/, "", d)
    out = type d ";" doc
    n = split(substr(code, index(code, ",") + 1), rest, ",")
    for (k = 1; k <= n; k++) {
        d = rest[k]
        sub(/;.*$/, "", d); gsub(/^[ \t]+|[ \t]+$/, "", d)
        sub(/^[ \t]+/, "", type)
        out = out " " type " " d ";" doc
    }
    return out
}

# The comment starting on line i (depth 0) ends on line e; when the lines
# after it up to a blank or comment line hold two or more declarations or
# macros and no block, they become one member group.
function group_after(i,    e, j, n) {
    for (e = i; e <= NR && index(substr(line[e], e == i ? index(line[e], "/*") + 2 : 1), "*/") == 0; e++) ;
    n = 0
    for (j = e + 1; j <= NR && line[j] !~ /^[ \t]*$/ && line[j] !~ /^[ \t]*(\/\*|\*)/; j++) {
        if (index(line[j], "/*") && line[j] !~ /\*\/[ \t]*$/) return   # a comment running on
        if (line[j] ~ /^[ \t]*#[ \t]*define/) { n++; continue }
        if (line[j] ~ /[{}]/ || line[j] ~ /^[ \t]*#/) return
        n += gsub(/;/, ";", line[j])
    }
    if (n < 2) return
    group_open[e] = 1
    group_close[j] = 1   # on the line after the run: a #define line's comment is the macro's
}

function quote_count(s,    n, k) {
    n = 0
    for (k = 1; k <= length(s); k++) if (substr(s, k, 1) == "\"") n++
    return n
}

# Whether the comment starting on line i ends right above a non-blank line.
function touches_code(i,    j) {
    for (j = i; j <= NR && index(substr(line[j], j == i ? index(line[j], "/*") + 2 : 1), "*/") == 0; j++) ;
    return j < NR && line[j + 1] !~ /^[ \t]*$/
}

# Brace depth, and whether the innermost open block is a function body;
# the comment state for the next line.
function track(s,    k, c, d, code) {
    code = ""
    for (k = 1; k <= length(s); k++) {
        c = substr(s, k, 1); d = substr(s, k, 2)
        if (incomment) { if (d == "*/") { incomment = 0; k++ } continue }
        if (d == "/*") { incomment = 1; k++; continue }
        if (d == "//") break
        code = code c
        if (c == "{") {
            depth++
            if (depth == 1 && prev_code !~ /(struct|union|enum)[^;]*$/ && code !~ /(struct|union|enum|=)/)
                body = 1
        } else if (c == "}") {
            depth--
            if (depth == 0) body = 0
        }
    }
    if (code ~ /[^ \t]/) prev_code = code
}
