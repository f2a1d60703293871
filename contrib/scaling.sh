#!/bin/sh
# Wall time, CPU time and peak memory (maximum resident set, GNU time) of the default job
# (`generate`, a hybrid field written as 16-bit PNG and float TIFF) and of a 48-frame
# `animate` sequence (PM 15 m/s, --method fft, float TIFF heights) at 512² … 8192², one
# sample spacing of 1 m. Prints one table row per run, with the wall and CPU time per
# sample and per sample per log2(N²), which stays flat where the cost grows as N log N.
#
#   contrib/scaling.sh [SEASYNTH] [OUT_DIR] [SIZES] [FRAMES]
#
# defaults: seasynth on the PATH, out/scaling, "512 1024 2048 4096 8192", 48. Frames are
# written to OUT_DIR and removed after each run (an 8192² frame is 256 MB).
set -eu
bin=${1:-seasynth}
out=${2:-out/scaling}
sizes=${3:-512 1024 2048 4096 8192}
frames=${4:-48}
mkdir -p "$out"
row() {
    # $1: label, $2: size, $3: samples, rest: command
    label=$1 n=$2 samples=$3
    shift 3
    /usr/bin/time -f "%e %U %S %M" -o "$out/time.txt" "$@" >/dev/null 2>&1
    read -r wall user sys kb <"$out/time.txt"
    awk -v l="$label" -v n="$n" -v s="$samples" -v w="$wall" -v u="$user" -v y="$sys" -v k="$kb" 'BEGIN {
        c = u + y; lg = log(n * n) / log(2);
        printf "| %s | %d² | %.2f s | %.2f s | %.0f MB | %.1f ns | %.1f ns | %.2f ns |\n",
            l, n, w, c, k / 1024, w / s * 1e9, c / s * 1e9, c / s / lg * 1e9 }'
}
echo "| run | size | wall | CPU | peak memory | wall / sample | CPU / sample | CPU / sample / log2 N² |"
echo "|---|---|---|---|---|---|---|---|"
for n in $sizes; do
    row generate "$n" "$((n * n))" "$bin" generate --size "$n" --extent "$n" \
        -o "$out/g$n.png" -o "$out/g$n.tif" -q
    rm -f "$out/g$n.png" "$out/g$n.tif" "$out/g$n.json"
done
for n in $sizes; do
    row "animate $frames frames" "$n" "$((n * n * frames))" "$bin" animate --method fft \
        --spectrum pierson-moskowitz --wind-speed 15 --size "$n" --extent "$n" \
        --frames "$frames" --format tif -o "$out/a$n" -q
    rm -rf "$out/a$n"
done
rm -f "$out/time.txt"
