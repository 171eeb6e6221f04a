#!/bin/sh
# figures.sh BUILD SRC... - `make figures`: run each chapter program (its
# source chapters/chNN/PROG.c, its binary BUILD/PROG) into out/figures/chNN,
# then draw the CSV files it wrote with every gnuplot script beside it
# (chapters/chNN/*.gp), as PNG and SVG in the same directory. Without
# gnuplot the programs still run (their PPM pictures and CSV files are
# written) and this says that the figures were not drawn; it exits 0.
# GNUPLOT names the gnuplot to use (default: gnuplot on the PATH).
set -u
build=$1; shift
gnuplot=${GNUPLOT:-gnuplot}
if command -v "$gnuplot" >/dev/null 2>&1; then have_gnuplot=1; else have_gnuplot=0; fi
mkdir -p out/figures; fail=0; chapters=""
for src in "$@"; do
    chdir=$(dirname "$src"); ch=$(basename "$chdir"); prog=$(basename "$src" .c)
    out=out/figures/$ch
    echo "figures: $prog -> $out"
    if ! "$build/$prog" "$out" >"$out.$prog.log" 2>&1; then
        echo "figures: $prog failed; its output is in $out.$prog.log"; fail=1; continue
    fi
    case " $chapters " in *" $chdir "*) ;; *) chapters="$chapters $chdir" ;; esac
done
if [ "$have_gnuplot" -eq 0 ]; then
    echo "figures: gnuplot is not installed, so no PNG or SVG was drawn; the CSV"
    echo "figures: files and PPM pictures are in out/figures/. Install gnuplot"
    echo "figures: (apt-get install gnuplot-nox) and run make figures again."
    exit $fail
fi
for chdir in $chapters; do
    out=out/figures/$(basename "$chdir")
    for gp in "$chdir"/*.gp; do
        [ -f "$gp" ] || continue
        for fmt in png svg; do
            if ! "$gnuplot" -c "$gp" "$out" "$fmt"; then
                echo "figures: $gp ($fmt) failed"; fail=1
            fi
        done
    done
    echo "figures: $out: $(ls "$out" | grep -c -E '\.(png|svg)$') PNG and SVG files"
done
exit $fail
