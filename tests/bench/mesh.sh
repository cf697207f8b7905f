# Sourced by the bench scripts (run.sh, plate.sh): make_mesh NAME SCAD makes
# $work/NAME.stl once, openscad's ASCII STL rewritten as binary by admesh.
make_mesh() { # name scad-source
    local stl="$work/$1.stl"
    [ -s "$stl" ] && return
    printf '%s\n' "$2" >"$work/$1.scad"
    openscad -q -o "$work/$1.ascii.stl" "$work/$1.scad"
    admesh -b "$stl" "$work/$1.ascii.stl" >/dev/null
    rm -f "$work/$1.ascii.stl"
}
