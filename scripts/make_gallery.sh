#!/usr/bin/env bash
# Renders the README's gallery into docs/images/ (about 10 minutes on 2 cores, most of it the
# path-traced reference, which is kept in build/gallery/ and reused by later runs).
# Usage: bash scripts/make_gallery.sh [--fresh]   (--fresh renders the reference again)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh >/dev/null
C=./build/caustica
out=docs/images
work=build/gallery
mkdir -p "$out" "$work"
[ "${1:-}" = "--fresh" ] && rm -f "$work/ref.exr"
font=DejaVuSans

# Adds a caption strip under an image: caption IN OUT TEXT
caption() {
  local w h
  read -r w h < <(oiiotool "$1" --echo "{TOP.width} {TOP.height}")
  # --paste puts the image below the top of the stack onto the top one.
  oiiotool --create "${w}x32" 3 --text:x=8:y=22:font=$font:size=16:color=1,1,1 "$3" \
    "$1" --create "${w}x$((h + 32))" 3 --paste +0+0 --paste "+0+$h" -o "$2"
}

echo "gallery: photon-mapped renders"
$C render scenes/tncg15-room.json --integrator photon --width 560 --height 315 --spp 32 --seed 1 -q \
  -o "$out/tncg15-room.png"
$C render scenes/cornell-spheres.json --integrator photon --width 400 --height 400 --spp 32 --seed 1 -q \
  -o "$out/cornell-spheres.png"
$C render scenes/caustic-ring.json --integrator photon --width 400 --height 400 --spp 32 --seed 1 -q \
  -o "$out/caustic-ring.png"
$C render scenes/material-spheres.json --integrator photon --width 816 --height 272 --spp 32 --seed 1 -q \
  -o "$out/material-spheres.png"
$C render scenes/volumetric-caustic.json --integrator photon --width 400 --height 400 --spp 64 --seed 1 -q \
  -o "$out/volumetric-caustic.png"
$C render scenes/mitsuba/principled.xml --integrator photon --width 640 --height 360 --spp 32 --seed 1 -q \
  -o "$out/mitsuba-principled.png"

echo "gallery: photon maps"
$C photons scenes/cornell-spheres.json --map both --width 320 --height 320 --seed 1 -q \
  -o "$work/splat.png"
caption "$work/splat.png" "$out/photons-splat.png" "photons: global and caustic maps"
$C photons scenes/cornell-spheres.json --map global --heatmap --width 320 --height 320 --seed 1 -q \
  -o "$work/heatmap.png"
caption "$work/heatmap.png" "$out/photons-heatmap.png" "global map density (heat map)"

echo "gallery: equal-time photon against path (reference: path, 8192 spp)"
size=256
seconds=10
[ -f "$work/ref.exr" ] || $C render scenes/cornell-spheres.json --integrator path --width $size --height $size \
  --spp 8192 --seed 1000 -q -o "$work/ref.exr"
relmse() { awk '/^relmse:/{printf "%.4f", $2}' "$1"; }
for integrator in photon path; do
  $C render scenes/cornell-spheres.json --integrator $integrator --width $size --height $size \
    --time $seconds --seed 1 --reference "$work/ref.exr" -o "$work/$integrator.png" 2>/dev/null \
    >"$work/$integrator.txt"
  caption "$work/$integrator.png" "$work/$integrator-captioned.png" \
    "$integrator, $seconds s: relMSE $(relmse "$work/$integrator.txt")"
done
oiiotool "$work/photon-captioned.png" "$work/path-captioned.png" --mosaic:pad=4 2x1 -o "$out/equal-time.png"
echo "gallery: relMSE photon $(relmse "$work/photon.txt"), path $(relmse "$work/path.txt") after $seconds s each"
ls -l "$out"
