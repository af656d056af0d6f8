#!/usr/bin/env bash
# Rebuilds the preset pictures of assets/README.md with our own command:
# each preset baked at 512² by `agesim bake --preset NAME`.
set -euo pipefail
cd "$(dirname "$0")/../../.."
out=$(mktemp -d)
for preset in fine rough goose-skin deep-pores article-fig14; do
  cargo run --release -q -- bake --preset "$preset" --size 512 --out "$out/$preset"
  cp "$out/$preset/height.png" "assets/docs/presets/$preset-height.png"
  cp "$out/$preset/normal.png" "assets/docs/presets/$preset-normal.png"
done
rm -rf "$out"
