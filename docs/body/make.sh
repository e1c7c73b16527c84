#!/usr/bin/env bash
# Regenerates the body pictures in this folder from the release build
# (run from the repository's root).
set -euo pipefail
b=target/release/shisen
$b render default --at 0.3 --view orbit:2.2,0.3,4.6 --out docs/body/stance.png
$b render scenes/slip_jabs.ron --at 1.84 --view orbit:0.35,0.7,3.6 --out docs/body/slip.png
$b render scenes/duck_hook.ron --at 2.2 --view orbit:1.9,0.3,4.6 --out docs/body/duck.png
$b render scenes/step_back.ron --at 1.75 --view orbit:1.6,0.3,4.6 --out docs/body/step.png
$b render scenes/circle.ron --at 3.5 --view orbit:2.4,0.5,4.6 --out docs/body/turn.png
