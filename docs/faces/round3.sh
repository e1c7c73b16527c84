#!/usr/bin/env bash
# The face's round 3 (issue 46), before and after: neutral and the six
# basic expressions in three views (the face camera at full intensity,
# three-quarter at 60 %, and first person at sparring distance), rendered
# by two builds of `shisen` and set in two rows (before over after) per
# view: docs/faces/round3_{face,three_quarter,first}.png. Needs python3
# with Pillow for the montage.
#   docs/faces/round3.sh BEFORE_BIN AFTER_BIN
set -euo pipefail
cd "$(dirname "$0")/../.."
before=${1:?the build before}; after=${2:?the build after}
tmp=$(mktemp -d)
for e in Neutral Happiness Surprise Fear Sadness Disgust Anger; do
  for i in 1.0 0.6; do
    cat > "$tmp/$e-$i.ron" <<SCENE
Scene(
    duration: 2.0,
    vh: (behaviour: (attacks: false), oculomotor: (fixation: (enabled: false))),
    timeline: [(at: 0.0, do: Emotion(emotion: $e, intensity: $i, speed: Fast))],
)
SCENE
  done
  for b in before after; do
    bin=$before; [ $b = after ] && bin=$after
    "$bin" render "$tmp/$e-1.0.ron" --at 1.5 --view face --size 300x340 --out "$tmp/face-$b-$e.png" >/dev/null
    "$bin" render "$tmp/$e-0.6.ron" --at 1.5 --view orbit:0.65,0.05,0.45 --size 300x340 --out "$tmp/three_quarter-$b-$e.png" >/dev/null
    "$bin" render "$tmp/$e-1.0.ron" --at 1.5 --view first --size 640x360 --out "$tmp/first-$b-$e.png" >/dev/null
  done
done
python3 - "$tmp" <<'PY'
import sys
from PIL import Image
tmp = sys.argv[1]
names = ["Neutral", "Happiness", "Surprise", "Fear", "Sadness", "Disgust", "Anger"]
for view, crop in [("face", None), ("three_quarter", None), ("first", (220, 40, 420, 260))]:
    cells = [[Image.open(f"{tmp}/{view}-{b}-{n}.png").convert("RGB") for n in names] for b in ("before", "after")]
    if crop:
        cells = [[c.crop(crop) for c in row] for row in cells]
    w, h = cells[0][0].size
    sheet = Image.new("RGB", (w * 7, h * 2), (30, 32, 38))
    for r, row in enumerate(cells):
        for k, c in enumerate(row):
            sheet.paste(c, (k * w, r * h))
    sheet.save(f"docs/faces/round3_{view}.png", optimize=True)
PY
rm -rf "$tmp"
