#!/usr/bin/env bash
# Contact sheet of the CENG795 texture and motion-blur scenes for the README: renders every
# regression/hw4_2019/*.xml and the two hw3_2019 motion-blur Cornell boxes with build/release/kiln at their own
# resolution and a few samples per pixel (the fit to 256x256 averages about 3x3 pixels into one, so the tiles are
# far less noisy than the spp suggests), fits each PNG preview into 256x256, writes the scene name on it and lays
# the twelve out 4x3 (row-major, in the order below) into docs/contact_sheet.png.
#
# usage: tools/contact_sheet.sh [SPP] [OUTPUT]     (defaults: 8, docs/contact_sheet.png)
# env:   KILN (default build/release/kiln), KILN_SHARED_DIR (default ../shared), THREADS (default 0: all cores),
#        FONT (default DejaVu Sans, package fonts-dejavu-core; the names are left out when it is missing)
# needs: oiiotool (Debian package openimageio-tools)
set -euo pipefail

cd "$(dirname "$0")/.."
spp="${1:-8}"
output="${2:-docs/contact_sheet.png}"
kiln="${KILN:-build/release/kiln}"
shared="${KILN_SHARED_DIR:-../shared}"
scenes_dir="$shared/scenes/ceng795/regression"
tile=256
font="${FONT:-/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf}"

[[ -x "$kiln" ]] || { echo "contact_sheet: $kiln not found (build the release preset first)" >&2; exit 2; }
command -v oiiotool >/dev/null || { echo "contact_sheet: oiiotool not found (apt-get install openimageio-tools)" >&2; exit 2; }

scenes=("$scenes_dir"/hw4_2019/*.xml "$scenes_dir/hw3_2019/cornellbox_dynamic.xml"
        "$scenes_dir/hw3_2019/cornellbox_boxes_dynamic.xml")
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

tiles=()
start=$SECONDS
for scene in "${scenes[@]}"; do
  name="$(basename "$scene" .xml)"
  t0=$SECONDS
  "$kiln" render "$scene" --spp "$spp" --threads "${THREADS:-0}" -q -o "$work/$name" >/dev/null
  png="$(ls "$work/$name"/*.png | head -n 1)"
  # Fit (keeping the aspect), pad to the tile, then the name in the top-left corner.
  label=()
  # Black under yellow, one pixel apart: readable on the white floors too.
  [[ -f "$font" ]] && label=(--text:x=7:y=19:size=14:font="$font":color=0,0,0 "$name"
                             --text:x=6:y=18:size=14:font="$font":color=1,1,0.4 "$name")
  oiiotool "$png" --fit:pad=1 "${tile}x${tile}" "${label[@]}" -o "$work/tile_$name.png"
  tiles+=("$work/tile_$name.png")
  echo "$name: $((SECONDS - t0)) s"
done
mkdir -p "$(dirname "$output")"
oiiotool "${tiles[@]}" --mosaic:pad=4 4x3 -o "$output"
echo "contact sheet: $output, ${#tiles[@]} scenes at $spp spp in $((SECONDS - start)) s"
