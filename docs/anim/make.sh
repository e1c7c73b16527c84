#!/usr/bin/env bash
# Regenerate the README's animation: the VH shifts its gaze 50 deg to the
# left (eyes first, then the head) and back, blinking with the shifts.
# Written by the program (APNG) from scenes/gaze_shift_blink.ron.
set -euo pipefail
cd "$(dirname "$0")/../.."
bin=target/release/shisen
[ -x "$bin" ] || cargo build --release
"$bin" render scenes/gaze_shift_blink.ron --view orbit:0.45,0.32,0.75 --size 400x300 \
  --at 0.3 --until 2.3 --fps 15 --out docs/anim/gaze_shift_blink.png

# A clean 7 m/s jab lands (scenes/jab_snaps_head.ron), seen from the VH's
# left, ten times slower than real time: the head snaps back and returns,
# the lids blink, the face winces.
"$bin" render scenes/jab_snaps_head.ron --view orbit:1.45,0.1,1.1 --size 400x300 \
  --at 1.06 --until 1.66 --fps 100 --slow 10 --out docs/anim/jab_snaps_head.png

# The whole body in the physics (scenes/knockdown.ron, pelvis: Balanced):
# a jab at 1 s does not put the VH down; a hard hook at 3.5 s does; it
# lies through the count and gets up. Seen from the side, real time.
"$bin" render scenes/knockdown.ron --view orbit:1.2,0.25,3.2 --size 400x300 \
  --at 3.3 --until 10.5 --fps 6 --out docs/anim/knockdown.png
