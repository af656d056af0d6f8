#!/bin/sh
# Regenerates the README's renders of the default head (needs ImageMagick's `convert`
# and a release build: `cargo build --release`). Run from the repository's root.
set -e
A=./target/release/agesim
T=$(mktemp -d)
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
# The default project with the old end at 90 years, so 85 is reachable.
echo '{"version": 2, "age": {"old_years": 90}}' > "$T/p.agesim.json"
P="--project $T/p.agesim.json"
for y in 25 45 65 85; do
  $A render $P --age-years $y --yaw 0 --pitch 0 --size 360x360 --map-size 2048 --out "$T/front-$y.png"
  $A render $P --age-years $y --yaw 35 --pitch 0 --size 360x360 --map-size 2048 --out "$T/side-$y.png"
  for v in front side; do
    convert "$T/$v-$y.png" -font DejaVu-Sans -fill white -pointsize 22 -annotate +12+30 "$y" "$T/$v-$y.png"
  done
done
convert \( "$T"/front-25.png "$T"/front-45.png "$T"/front-65.png "$T"/front-85.png +append \) \
        \( "$T"/side-25.png "$T"/side-45.png "$T"/side-65.png "$T"/side-85.png +append \) \
        -append docs/renders/ages.png
$A render $P --age-years 75 --no-hair --map-size 4096 --distance 0.2 --yaw 50 --pitch 20 --size 400x400 --out "$T/eye.png"
$A render $P --age-years 75 --no-hair --map-size 4096 --distance 0.2 --yaw 15 --pitch -12 --size 400x400 --out "$T/fold.png"
convert "$T/eye.png" "$T/fold.png" +append docs/renders/close-up-75.png
$A render --compare 0.1,0.95 --size 360x360 --out docs/renders/compare.png
# The shape at 25 and 85 (t of 25 and 85 years with the old end at 90), front and profile.
$A render $P --compare 0.0714,0.9286 --no-hair --yaw 0 --pitch 0 --distance 0.6 --size 360x360 --out "$T/shape-front.png"
$A render $P --compare 0.0714,0.9286 --no-hair --yaw 90 --pitch 0 --distance 0.6 --size 360x360 --out "$T/shape-profile.png"
convert "$T/shape-front.png" "$T/shape-profile.png" -append docs/renders/shape-25-85.png
rm -rf "$T"
