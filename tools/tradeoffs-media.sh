#!/bin/sh
# tradeoffs-media.sh - `make tradeoffs-media`: error against time of the
# volumetric path tracer (ch. 11, `render integrator volpath`) on
# scenes/smoky-cbox.scn and scenes/cloud.scn. For each scene a long
# volpath reference (REF_SPP samples at half the scene's resolution, seed
# 7) is rendered once into out/tradeoffs-media/; `svet converge` then
# renders the scene as shipped (the baseline) and with one knob changed
# (Russian roulette off; a lower maxdepth, biased by design), and
# single scattering by ray marching (`render integrator volsingle`) at
# the march steps of STEPS, at the sample counts of SPP_LIST, and the
# volume photon map (`render integrator volphoton`) with the photon
# counts of PHOTONS at the sample counts of VP_SPP_LIST; `svet
# converge --report` turns each series into a table. The times are
# CPU-seconds by default (`svet converge --clock cpu`, all threads
# together), which the machine's other jobs hardly change. Writes
# docs/tradeoffs-media.md.
# usage: sh tools/tradeoffs-media.sh   (environment: SVET (build/float/svet),
#        CLOCK (cpu, or wall),
#        SPP_LIST (1,2,4,...,128), STEPS (0.1 0.05 0.025), THREADS (0),
#        PHOTONS (50000 200000), VP_SPP_LIST (1,2,4,...,32),
#        REF_SPP (2048), OUT, DOC,
#        DOC_ONLY=1 to write the document from the last run's series)
set -eu
svet=${SVET:-build/float/svet}
clock=${CLOCK:-cpu}
spps=${SPP_LIST:-1,2,4,8,16,32,64,128}
threads=${THREADS:-0}
refspp=${REF_SPP:-2048}
steps=${STEPS:-0.1 0.05 0.025}
photons=${PHOTONS:-50000 200000}
vpspps=${VP_SPP_LIST:-1,2,4,8,16,32}
out=${OUT:-out/tradeoffs-media}
doc=${DOC:-docs/tradeoffs-media.md}
[ -x "$svet" ] || { echo "tradeoffs-media: no $svet (make first)" >&2; exit 1; }
case $clock in
cpu) secs="CPU-seconds" ;;
wall) secs="seconds" ;;
*) echo "tradeoffs-media: CLOCK=$clock: expected cpu or wall" >&2; exit 1 ;;
esac
mkdir -p "$out"
t0=$(date +%s)
load0=$(cut -d' ' -f1-3 /proc/loadavg)
# DOC_ONLY=1: write the document again from the last run's series.
[ "${DOC_ONLY:-0}" = 1 ] && names= || names="smoky-cbox cloud"
for name in $names; do
    scene=scenes/$name.scn
    case $name in smoky-cbox) res=64x64 ;; cloud) res=80x60 ;; esac
    if [ ! -f "$out/$name-ref.exr" ]; then
        echo "tradeoffs-media: $name: the reference, $refspp spp at $res" >&2
        "$svet" render "$scene" --set resolution=$res --spp "$refspp" \
            --seed 7 --threads "$threads" -q -o "$out/$name-ref.exr" \
            --variance "$out/$name-ref-var.exr"
    fi
    mkdir -p "$out/$name"
    rm -f "$out/$name"/*.csv
    set -- "baseline" "roulette=off --set roulette=off" \
        "maxdepth=2 --set maxdepth=2"
    for h in $steps; do
        set -- "$@" "volsingle-step=$h --set integrator=volsingle --set volsingle.step=$h"
    done
    for n in $photons; do
        set -- "$@" "volphoton-photons=$n --set integrator=volphoton --set volphoton.photons=$n"
    done
    for m in "$@"; do
        # shellcheck disable=SC2086 # the label, then the settings
        set -- $m
        label=$1; shift
        # the volume photon map's pre-pass is in every point of its series
        case $label in volphoton-*) list=$vpspps ;; *) list=$spps ;; esac
        echo "tradeoffs-media: $name: $label" >&2
        "$svet" converge "$scene" --ref "$out/$name-ref.exr" --seed 1 \
            --spp-list "$list" --clock "$clock" --threads "$threads" \
            --out "$out/$name" \
            --label "$label" --no-plot -q "$@" >/dev/null
    done
    set -- "$out/$name/baseline.csv" "$out/$name/roulette=off.csv" \
        "$out/$name/maxdepth=2.csv"
    for h in $steps; do
        set -- "$@" "$out/$name/volsingle-step=$h.csv"
    done
    for n in $photons; do
        set -- "$@" "$out/$name/volphoton-photons=$n.csv"
    done
    "$svet" converge --report "$@" > "$out/$name.md"
done
if [ "${DOC_ONLY:-0}" = 1 ]; then
    . "$out/run.env"
else
    t1=$(date +%s)
    load1=$(cut -d' ' -f1-3 /proc/loadavg)
    printf "t0=%s; t1=%s; load0='%s'; load1='%s'\n" "$t0" "$t1" "$load0" \
        "$load1" > "$out/run.env"
fi
cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1)
{
    echo "# Media (ch. 11): the estimators, error against time"
    echo
    echo "Written by \`make tradeoffs-media\` (tools/tradeoffs-media.sh) on"
    echo "$(date -u +%Y-%m-%d) UTC, $cpu, $(nproc) cores, threads $threads, in"
    echo "$((t1 - t0)) s (load average $load0 before, $load1 after: other"
    if [ "$clock" = cpu ]; then
        echo "work shared the machine; the times are CPU-seconds, \`svet"
        echo "converge --clock cpu\`, all threads together, which the load"
        echo "hardly changes). Each scene against its"
    else
        echo "work shared the machine, so the wall-clock times are noisy)."
        echo "Each scene against its"
    fi
    echo "own volpath reference of $refspp spp (seed 7, half the scene's"
    echo "resolution); the series render with seed 1 at $spps spp. \`svet"
    echo "converge --report\` (see docs/tradeoffs.md, How to read the tables)."
    echo "\`maxdepth=2\` is biased by design: it drops the light of longer"
    echo "paths, which a medium's multiple scattering carries."
    echo "\`volsingle-step=H\` is \`render integrator volsingle\`, single"
    echo "scattering by ray marching with step H (scene units: the room is 2"
    echo "wide, the cloud's box 3): biased by design as well against the multiply scattering"
    echo "reference, its error levelling off at the light of the paths that"
    echo "scatter more than once in the medium; a smaller step costs time"
    echo "per sample and lowers the march's noise, not that bias."
    echo "\`volphoton-photons=N\` is \`render integrator volphoton\` (the"
    echo "volume photon map, Jensen & Christensen 1998) with N photons from"
    echo "the lights and the scene's other volphoton keys at their defaults"
    echo "(scenes/README.md), at $vpspps spp; each point's time"
    echo "includes its photon pass."
    for name in smoky-cbox cloud; do
        echo
        echo "## $name (scenes/$name.scn)"
        echo
        cat "$out/$name.md"
        echo
        echo "The baseline's series: relative RMSE (the reference's noise"
        echo "removed) against samples per pixel and $secs."
        echo
        echo "| spp | $secs | relative RMSE |"
        echo "|---:|---:|---:|"
        grep -v '^#' "$out/$name/baseline.csv" | awk -F, 'NR > 1 {
            printf "| %d | %.3g | %.3g |\n", $2, $3, $16 }'
    done
} > "$doc"
echo "tradeoffs-media: wrote $doc" >&2
