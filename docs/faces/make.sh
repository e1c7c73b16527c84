#!/usr/bin/env bash
# Regenerate the expression renders shown in the README: neutral and the
# six basic expressions, at two mesh resolutions, offscreen (lavapipe works).
set -euo pipefail
cd "$(dirname "$0")/../.."
bin=target/release/shisen
[ -x "$bin" ] || cargo build --release
tmp=$(mktemp -d)
for rows in 32 100; do
  for e in Neutral Happiness Surprise Fear Sadness Disgust Anger; do
    cat > "$tmp/face.ron" <<SCENE
Scene(
    duration: 2.0,
    vh: (behaviour: (attacks: false), oculomotor: (fixation: (enabled: false)), face: (rows: $rows)),
    timeline: [(at: 0.0, do: Emotion(emotion: $e, speed: Fast))],
)
SCENE
    "$bin" render "$tmp/face.ron" --at 1.5 --view face --size 360x400 \
      --out "docs/faces/$(echo "$e" | tr 'A-Z' 'a-z')_$rows.png"
  done
done
rm -rf "$tmp"
