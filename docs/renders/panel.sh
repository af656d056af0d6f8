#!/bin/sh
# Renders every head of the panel for a blind rating (the issue "every head ages as well as
# the default one"): for each head, rating.sh's four images (25 | 80 front, three-quarter,
# profile; close-ups at 75) and single front renders at 25, 45, 65 and 85 years (the
# apparent-age protocol), in OUT_DIR/HEAD/. The heads: the scan (the default head), the
# MakeHuman head, the four panel heads of assets/heads/panel (three with their colour maps)
# and a dense head of our own (the European woman split twice: 142k triangles).
# Needs a release build (or AGESIM=path to a binary), ImageMagick and python3.
# Usage: panel.sh OUT_DIR
set -e
A=${AGESIM:-./target/release/agesim}
O=${1:?usage: panel.sh OUT_DIR}
mkdir -p "$O"
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
P=assets/heads/panel
python3 docs/renders/subdivide.py $P/caucasian-female.obj "$O/dense-female.obj" 2 > /dev/null
one_head() {
  name=$1; mpu=$2; shift 2
  mkdir -p "$O/$name"
  MPU=$mpu sh docs/renders/rating.sh "$O/$name" "$@" > /dev/null
  dist=$(awk -v u="$mpu" 'BEGIN { printf "%g", 0.72 / u }')
  for y in 25 45 65 85; do
    # The default age range ends at 80 (t = 1): 85 is rendered on a range that reaches it.
    old=80; [ "$y" -gt 80 ] && old=$y
    $A render --age-years $y --set age.old_years=$old --size 560x600 --distance "$dist" --yaw 0 --pitch 0 \
      --map-size 2048 "$@" --out "$O/$name/age-$y.png" > /dev/null
  done
  echo "$name done"
}
one_head scan 1
one_head makehuman 0.1 --mesh assets/heads/makehuman/mh_head.obj --landmarks assets/heads/makehuman/landmarks.json
one_head african-female 0.1 --mesh $P/african-female.obj --colour-map $P/middleage_darkskinned_female_diffuse.jpg
one_head african-male 0.1 --mesh $P/african-male.obj --colour-map $P/middleage_darkskinned_male_diffuse.jpg
one_head caucasian-female 0.1 --mesh $P/caucasian-female.obj --colour-map $P/middleage_lightskinned_female_diffuse2.jpg
one_head asian-male 0.1 --mesh $P/asian-male.obj
one_head dense-female 0.1 --mesh "$O/dense-female.obj" --colour-map $P/middleage_lightskinned_female_diffuse2.jpg
