#!/usr/bin/env bash
# Renders the scenes the test suite uses with two kiln binaries and compares the SHA-1 of every output image's
# pixels, not of its metadata (timings differ): the SHA-1 of the EXR's pixel chunks as written (both binaries
# compress with the same OpenEXR, so equal chunks are equal pixels), and where those differ the SHA-1 of the
# decoded pixels (iinfo --hash, from openimageio-tools), which decides. For refactors that must not change a pixel.
#
#   tools/same_pixels.sh BEFORE_KILN AFTER_KILN [OUT_DIR]
#
# Each case renders at low spp with a fixed seed, across the integrators and their strategies (Kiln's path tracer,
# the course path tracer and ray tracer, textures, motion, depth of field, dielectrics, pbrt). Prints one line per
# image, "same" or "DIFFERENT", and exits 1 when any image differs or a render fails in one binary only.
# KILN_SHARED (default: ../shared beside the checkout) holds the course and pbrt scenes; ONLY=REGEX keeps the cases
# whose name matches.
set -u
if [ $# -lt 2 ]; then
  sed -n '2,12p' "$0"
  exit 2
fi
before=$(realpath "$1")
after=$(realpath "$2")
out=${3:-/tmp/same_pixels}
repo=$(cd "$(dirname "$0")/.." && pwd)
shared=${KILN_SHARED:-$repo/../shared}
command -v iinfo >/dev/null || { echo "same_pixels: needs iinfo (openimageio-tools)" >&2; exit 2; }

# SHA-1 of a single-part scanline EXR's pixel chunks: everything after the header and the chunk offset table
# (whose values move with the header's length). Empty for other files.
chunk_hash() {
  python3 - "$1" <<'PY'
import hashlib, struct, sys
data = open(sys.argv[1], "rb").read()
if data[:4] != b"\x76\x2f\x31\x01" or data[5] & 0x1a:  # magic; tiled, deep or multi-part
    sys.exit(0)
pos = 8
while data[pos] != 0:  # attributes: name\0 type\0 size value
    pos = data.index(b"\0", data.index(b"\0", pos) + 1) + 1
    size = struct.unpack_from("<i", data, pos)[0]
    pos += 4 + size
first_chunk = struct.unpack_from("<Q", data, pos + 1)[0]
print(hashlib.sha1(data[first_chunk:]).hexdigest())
PY
}
pixel_hash() { iinfo --hash "$1" | sed -n 's/.*SHA-1: *//p'; }

common=(--seed 7 -q --threads 2)
cases=()  # "name|scene|extra args"
add() { cases+=("$1|$2|${3:-}"); }

# The repository's own scenes and test data.
for f in "$repo"/scenes/*.xml "$repo"/scenes/cs171/configs/*.json "$repo"/tests/data/cs171/*.json; do
  add "$(basename "${f%.*}")" "$f" "--spp 4"
done
for f in furnace_sphere furnace_box lookat_hit rotate_hit all_directives instancing includes/main; do
  add "pbrt_${f//\//_}" "$repo/tests/data/pbrt/$f.pbrt" "--spp 4"
done
# Every CENG795 and CS171 scene under the shared folder (the course scene tests load them all), at 2 spp and at the
# course's 1-spp pixel-centre convention.
while IFS= read -r f; do
  rel=${f#"$shared"/scenes/}
  name=${rel//\//_}
  add "${name%.*}" "$f" "--spp 2"
  add "${name%.*}_1spp" "$f" "--spp 1"
done < <(find "$shared/scenes/ceng795" "$shared/scenes/cs171" \( -name '*.xml' -o -name '*.json' \) | sort)
add killeroo_simple "$shared/scenes/pbrt/killeroos/killeroo-simple.pbrt" "--spp 4"

# Kiln's rules and each of its path-tracing strategies on course scenes with glass, mirrors, textures and area
# lights; the course's roulette in both modes; pixel filters, AOVs and a crop.
pt=$shared/scenes/ceng795/pathTracing
dl=$shared/scenes/ceng795/directLighting
for scene in "$pt/cornellbox_jaroslav_path_glass.xml" "$shared/scenes/ceng795/regression/hw4_2019/bump_mapping_transformed.xml" \
             "$dl/cornellbox_jaroslav_glossy_area_ellipsoid.xml" "$shared/scenes/ceng795/veach-ajar/scene.xml"; do
  base=$(basename "$(dirname "$scene")")_$(basename "${scene%.xml}")
  add "${base}_kiln" "$scene" "--spp 2 --rules kiln"
  for s in uniform cosine brdf nee mis+rr; do add "${base}_${s}" "$scene" "--spp 2 --strategy $s"; done
done
add glass_rr_literal "$pt/cornellbox_jaroslav_path_glass.xml" "--spp 2 --rr true --course-roulette literal"
add glass_rr_expected "$pt/cornellbox_jaroslav_path_glass.xml" "--spp 2 --rr true --course-roulette expected"
add glass_unlimited "$pt/cornellbox_jaroslav_path_glass.xml" "--spp 2 --strategy mis+rr --max-depth -1"
add glass_clamp "$pt/cornellbox_jaroslav_path_glass.xml" "--spp 2 --strategy mis --clamp 2"
add ellipsoid_physical "$dl/cornellbox_jaroslav_glossy_area_ellipsoid.xml" "--spp 2 --physical-lights"
add default_filters "$repo/scenes/default.xml" "--spp 4 --filter mitchell"
add default_gaussian "$repo/scenes/default.xml" "--spp 4 --filter gaussian:2"
add default_crop_range "$repo/scenes/default.xml" "--spp 8 --spp-range 2:6 --crop 10,90,20,70"
add default_adaptive "$repo/scenes/default.xml" "--spp 16 --adaptive 0.05"
add default_aovs "$repo/scenes/default.xml" "--spp 4 --aov all"
add default_bvh "$repo/scenes/default.xml" "--spp 4 --accel bvh"
add killeroo_path_subdivide "$repo/scenes/killeroo_path.xml" "--spp 2 --subdivide 1"

rm -rf "$out"
mkdir -p "$out"
differ=0 images=0 ran=0
for c in "${cases[@]}"; do
  IFS='|' read -r name scene extra <<<"$c"
  [[ -z "${ONLY:-}" || "$name" =~ $ONLY ]] || continue
  ran=$((ran + 1))
  # shellcheck disable=SC2086  # extra holds several arguments
  for side in before after; do
    bin=$before
    [ $side = after ] && bin=$after
    timeout 600 "$bin" render "$scene" -o "$out/$side/$name" "${common[@]}" $extra >/dev/null 2>"$out/$name.$side.err"
    echo $? >"$out/$name.$side.rc"
  done
  rb=$(cat "$out/$name.before.rc") ra=$(cat "$out/$name.after.rc")
  if [ "$rb" != "$ra" ]; then
    echo "DIFFERENT exit  $name: before $rb, after $ra ($(head -c 200 "$out/$name.after.err"))"
    differ=1
    continue
  fi
  found=0
  for img in "$out/before/$name"/*.exr; do
    [ -e "$img" ] || continue
    found=1
    images=$((images + 1))
    other="$out/after/$name/$(basename "$img")"
    hb=$(chunk_hash "$img")
    ha=$( [ -e "$other" ] && chunk_hash "$other")
    if [ -z "$hb" ] || [ "$hb" != "$ha" ]; then
      hb=$(pixel_hash "$img")
      ha=$( [ -e "$other" ] && pixel_hash "$other")
    fi
    if [ -n "$hb" ] && [ "$hb" = "$ha" ]; then
      echo "same       $name/$(basename "$img") $hb"
    else
      echo "DIFFERENT  $name/$(basename "$img") before $hb after ${ha:-missing}"
      differ=1
    fi
  done
  [ $found = 1 ] || echo "no image   $name (exit $rb: $(head -c 200 "$out/$name.before.err"))"
done
echo "same_pixels: $ran cases, $images images, $([ $differ = 0 ] && echo 'all pixels identical' || echo 'DIFFERENCES')"
exit $differ
