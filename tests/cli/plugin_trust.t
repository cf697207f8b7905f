#!/usr/bin/env bash
# A plugin is code lamina runs: LAMINA_PLUGINS=DIR loads DIR/NAME.so only
# when the file opened and every directory from where it really is (a
# link followed) and from DIR, up to /, belong to root or the user and are
# not writable by group or others (a sticky directory such as /tmp passes:
# in it nobody but an entry's owner may replace the entry). A link into a
# world-writable directory, a subdirectory of one, a FIFO and a file of
# another user are refused with a message naming the culprit; a good
# directory loads. The directories are made here, at test time.
. "$(dirname "$0")/lib.sh"

ROOT=$(cd "$TESTS/.." && pwd)
SO="$BUILD/plugins/cli-binary.so"
[ -f "$SO" ] || SO="$ROOT/plugins/cli-binary.so"
MODEL="$M/thesis_cube_hole.ug"

# trusted DIR: whether DIR and every directory above it passes the rule
# (owner root or me; not group/other-writable unless sticky)
me=$(id -u)
trusted() {
    local d
    d=$(cd "$1" && pwd -P) || return 1
    while :; do
        read -r uid mode < <(stat -c '%u %a' "$d")
        [ "$uid" = 0 ] || [ "$uid" = "$me" ] || return 1
        # mode in octal, sticky bit 01000
        (( (8#$mode & 8#022) == 0 || (8#$mode & 8#1000) != 0 )) || return 1
        [ "$d" = / ] && return 0
        d=$(dirname "$d")
    done
}

# slice_with DIR OUT: slice with the cli-binary profile, plugins from DIR only
slice_with() {
    run env LAMINA_PLUGINS="$1" "$LAMINA" slice "$MODEL" -m cli-binary -w 1 -o "$2"
}

B="$TMP/base"
mkdir -m 755 "$B"
if trusted "$B"; then
    # ---- a good directory loads ----
    mkdir -m 755 "$B/good"
    cp "$SO" "$B/good/cli-binary.so"
    chmod 644 "$B/good/cli-binary.so"
    slice_with "$B/good" "$TMP/good.cli"
    is "$RC" 0 "a plugin in a 0755 directory of a trusted tree loads ($ERR)"
    # the plugin's own output, not the text dialect's: the header ends in $$HEADEREND
    grep -aq 'HEADEREND' "$TMP/good.cli"; ok $? "... and writes the binary CLI"
    # a sticky world-writable directory of root or mine, as /tmp is
    mkdir -m 755 "$B/sticky"
    chmod 1777 "$B/sticky"
    mkdir -m 755 "$B/sticky/mine"
    cp "$SO" "$B/sticky/mine/cli-binary.so"
    slice_with "$B/sticky/mine" "$TMP/sticky.cli"
    is "$RC" 0 "a directory of mine inside a sticky 1777 one loads (nobody else may replace it)"
else
    ok 1 "# SKIP $B is under a directory others may write: no trusted place for a plugin here"
    ok 1 "# SKIP (the binary CLI)"
    ok 1 "# SKIP (sticky)"
fi

# ---- a link to a file in a world-writable directory ----
mkdir -m 755 "$B/ww" "$B/links"
chmod 777 "$B/ww"
cp "$SO" "$B/ww/cli-binary.so"
chmod 644 "$B/ww/cli-binary.so"
ln -s "$B/ww/cli-binary.so" "$B/links/cli-binary.so"
slice_with "$B/links" "$TMP/link.cli"
like "$RC $ERR" "^1 lamina: refusing plugin .*/links/cli-binary\\.so, which is .*/ww/cli-binary\\.so: directory .*/ww is writable by others than its owner \\(mode 777\\)" \
    "a link into a 0777 directory: refused, naming that directory"
[ ! -e "$TMP/link.cli" ]; ok $? "... and nothing written"

# ---- a 0755 directory inside a world-writable one ----
mkdir -m 755 "$B/ww/sub"
cp "$SO" "$B/ww/sub/cli-binary.so"
slice_with "$B/ww/sub" "$TMP/sub.cli"
like "$RC $ERR" "^1 lamina: refusing plugin .*/ww/sub/cli-binary\\.so: directory .*/ww is writable by others than its owner" \
    "a 0755 subdirectory of a 0777 directory: refused"
# the same tree with the sticky bit on the 0777 directory is the /tmp case
chmod 1777 "$B/ww"
if trusted "$B"; then
    slice_with "$B/ww/sub" "$TMP/sub.cli"
    is "$RC" 0 "... and loads once that directory is sticky (1777)"
else
    ok 1 "# SKIP (no trusted place)"
fi
chmod 777 "$B/ww"

# ---- a link in a world-writable directory to a good file ----
# (whoever may write the directory named may point the link anywhere)
if trusted "$B"; then
    mkdir -m 777 "$B/wwl"
    chmod 777 "$B/wwl"
    ln -s "$B/good/cli-binary.so" "$B/wwl/cli-binary.so"
    slice_with "$B/wwl" "$TMP/wwl.cli"
    like "$RC $ERR" "^1 lamina: refusing plugin .*/wwl/cli-binary\\.so, which is .*/good/cli-binary\\.so: directory .*/wwl is writable by others than its owner" \
        "a good file named through a link in a 0777 directory: refused"
else
    ok 1 "# SKIP (no trusted place)"
fi

# ---- a FIFO named like a plugin: refused at once, not waited on ----
mkdir -m 755 "$B/fifo"
mkfifo "$B/fifo/cli-binary.so"
slice_with_timeout() { run timeout 60 env LAMINA_PLUGINS="$1" "$LAMINA" slice "$MODEL" -m cli-binary -w 1 -o "$2"; }
slice_with_timeout "$B/fifo" "$TMP/fifo.cli"
like "$RC $ERR" "^1 lamina: refusing plugin .*/fifo/cli-binary\\.so: not a regular file" "a FIFO as a plugin: refused at once"

# ---- a file of another user (root can make one) ----
if [ "$me" = 0 ] && id nobody >/dev/null 2>&1; then
    mkdir -m 755 "$B/other"
    cp "$SO" "$B/other/cli-binary.so"
    chown nobody "$B/other/cli-binary.so"
    slice_with "$B/other" "$TMP/other.cli"
    like "$RC $ERR" "^1 lamina: refusing plugin .*/other/cli-binary\\.so: the file belongs to uid [0-9]+, neither root nor you" \
        "a plugin file of another user: refused"
    chown nobody "$B/other"
    chown root "$B/other/cli-binary.so"
    slice_with "$B/other" "$TMP/other.cli"
    like "$RC $ERR" "^1 lamina: refusing plugin .*/other/cli-binary\\.so: directory .*/other belongs to uid [0-9]+" \
        "a plugin in a directory of another user: refused"
else
    ok 1 "# SKIP not root: cannot give a file to another user"
    ok 1 "# SKIP (the directory)"
fi

done_testing
