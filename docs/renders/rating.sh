#!/bin/sh
# Writes the four images of a blind rating (docs: ../AGING-RUBRIC in the issue; each rater
# sees only these and the rubric): the default head at 25 | 80 from the front, at three-
# quarter and in profile, and three close-ups at 75 (the crow's feet, the nasolabial fold,
# the face from the brows to the mouth), each framed on the head's landmarks.
# Needs ImageMagick's `convert` and a release build. Usage: rating.sh OUT_DIR [extra render flags]
# Any head: pass its flags (`--mesh`, `--landmarks`, `--colour-map`, …) and set MPU to its
# metres per mesh unit (0.1 for decimetres) so the camera stands as far in metres.
set -e
A=${AGESIM:-./target/release/agesim}
O=${1:?usage: rating.sh OUT_DIR [render flags]}
shift
mkdir -p "$O"
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
# t of 25 and 80 years on the default age range, 20-80.
MPU=${MPU:-1}
d() { awk -v m="$1" -v u="$MPU" 'BEGIN { printf "%g", m / u }'; }
C="--compare 0.0833,1.0 --size 560x600 --distance $(d 0.72) --map-size 2048"
$A render $C --yaw 0 --pitch 0 "$@" --out "$O/1-front.png"
$A render $C --yaw 35 --pitch 0 "$@" --out "$O/2-three-quarter.png"
$A render $C --yaw 90 --pitch 0 "$@" --out "$O/3-profile.png"
T=$(mktemp -d)
# Each close-up aims at the head's own landmarks (the outer eye corner, between the nose
# wing and the mouth corner, the face's middle), so it frames the same part of any head.
$A render --age-years 75 --map-size 4096 --look-at exocanthion_l --distance $(d 0.12) --yaw 50 --pitch 20 --size 400x400 "$@" --out "$T/eye.png"
$A render --age-years 75 --map-size 4096 --look-at alare_l,cheilion_l --distance $(d 0.12) --yaw 15 --pitch -12 --size 400x400 "$@" --out "$T/fold.png"
$A render --age-years 75 --map-size 4096 --look-at glabella,subnasale --distance $(d 0.25) --yaw 0 --pitch 5 --size 400x400 "$@" --out "$T/face.png"
convert "$T/eye.png" "$T/fold.png" "$T/face.png" +append "$O/4-close-ups-75.png"
rm -rf "$T"
