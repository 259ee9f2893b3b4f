#!/usr/bin/env bash
# The README's denoising pictures: the Cornell box at few samples raw, the same
# render denoised by Open Image Denoise, and a converged reference, side by side.
#
#   docs/denoise/make_images.sh [SPP] [REFERENCE_SPP] [SIZE] [SCENE]
#                                (default 16, 2048, 128x128, scenes/cornell_box.toml)
#
# Needs an rt built with the denoise feature (README: Denoising), found as $RT or
# target/release/rt. Writes docs/images/denoise_{raw,denoised,reference}.png.
set -euo pipefail
cd "$(dirname "$0")/../.."
rt="${RT:-target/release/rt}"
spp="${1:-16}"
reference_spp="${2:-2048}"
size="${3:-128x128}"
scene="${4:-scenes/cornell_box.toml}"
out=docs/images
# Raw and denoised with the same seed: the same samples, one image denoised.
"$rt" render "$scene" --size "$size" --spp "$spp" --seed 1 -o "$out/denoise_raw.png"
"$rt" render "$scene" --size "$size" --spp "$spp" --seed 1 --denoise -o "$out/denoise_denoised.png"
"$rt" render "$scene" --size "$size" --spp "$reference_spp" --seed 2 -o "$out/denoise_reference.png"
ls -l "$out"/denoise_*.png
