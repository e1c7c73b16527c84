#!/usr/bin/env bash
# Seed the fuzz corpus from the project's own scene, gains, muscle-database
# and emotion-script files (the corpus is kept in the repository), then fuzz:
# `cd fuzz && RUSTC_BOOTSTRAP=1 cargo fuzz run --sanitizer none scene corpus/scene`.
set -euo pipefail
cd "$(dirname "$0")/.."
mkdir -p fuzz/corpus/scene
for f in scenes/*.ron scenes/gains/*.ron scenes/face/*.ron scenes/face/*.txt scenes/studies/*.ron; do
  cp "$f" "fuzz/corpus/scene/$(echo "$f" | tr / _)"
done
