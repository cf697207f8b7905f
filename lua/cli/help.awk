# lua/API.md -> the REPL's help entries (a C file; see help.h). Run by the
# Makefile at build time, so help() always says what the document says.
#
# Every `##` and `###` heading starts an entry that runs to the next
# heading. Its key: a heading that starts with a code span names what it
# documents, up to the first character that is not part of a name
# (`lamina.load(path)` -> lamina.load, `model:slice{...}` -> model:slice,
# `## lamina.axes` -> lamina.axes); any other heading is its own key in
# lower case (`## layer` -> layer, `## Conventions` -> conventions).
# a C string literal of s and a newline, one character at a time (gsub's
# backslashes differ between awks); `?` escaped so no trigraph can form
function cstr(s,    out, i, ch) {
    out = ""
    for (i = 1; i <= length(s); i++) {
        ch = substr(s, i, 1)
        if (ch == "\\" || ch == "\"" || ch == "?") out = out "\\" ch
        else if (ch == "\t") out = out "\\t"
        else out = out ch
    }
    return "\"" out "\\n\""
}
function flush() {
    if (key == "") return
    while (n > 0 && body[n] == "") n--
    printf "    { \"%s\",\n", key
    for (i = 1; i <= n; i++) printf "      %s\n", cstr(body[i])
    printf "    },\n"
    key = ""
}
BEGIN {
    print "/* Generated from lua/API.md by lua/cli/help.awk: do not edit. */"
    print "#include \"help.h\""
    print "const lam_help_entry lam_help_entries[] = {"
}
/^```/ { fence = !fence }
!fence && /^###? / {
    flush()
    title = $0
    sub(/^#+ /, "", title)
    if (title ~ /^`/) {
        key = substr(title, 2)
        match(key, /^[A-Za-z_][A-Za-z0-9_.:]*/)
        key = substr(key, 1, RLENGTH)
    } else {
        key = tolower(title)
        gsub(/`/, "", key)
        gsub(/"/, "", key)
    }
    n = 1
    body[1] = title
    gsub(/`/, "", body[1])
    next
}
!fence && /^# / { flush(); next }
key != "" { body[++n] = $0 }
END {
    flush()
    print "    { 0, 0 },"
    print "};"
}
