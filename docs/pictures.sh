#!/usr/bin/env bash
# Makes the pictures and the movie of README.md and docs/ with the software renderer:
# each is one `ontogen run`, written into a scratch folder and copied under its name.
#
#   bash docs/pictures.sh [path/to/ontogen]     (default: build/apps/ontogen)
#
# The pictures are the same bytes on every machine that builds the same ontogen; the
# movies are as ffmpeg encodes them. Takes a few minutes (the evolution is most of it).
set -euo pipefail
cd "$(dirname "$0")/.."
ontogen=${1:-build/apps/ontogen}
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

# picture NAME SIZE [ARGS...]: models/NAME.cell's last frame as docs/images/NAME.png.
picture() {
  local name=$1 size=$2
  shift 2
  "$ontogen" run "models/$name.cell" --format png --size "$size" --out "$scratch/$name" "$@" 2>/dev/null
  cp "$scratch/$name/$name.png" "docs/images/$name.png"
}

picture flower 400x400
picture horn_cylinders 400x400
picture horn_gc 400x400
picture cube 400x400
picture replicator 400x400
picture plant_ceiling 400x400
picture triangles 500x400
picture triangles_attracted 500x400
picture orchard 800x800
picture colony 800x800
picture statics_binary_tree 800x800 --define R=0.2 --view 35,20
picture creature 640x400 --define SEGMENTS=6 --define DUTY=0.5
picture windy_tree 400x400

# The first picture of README.md: four models side by side.
for name in flower orchard colony statics_binary_tree; do
  extra=()
  [ "$name" = statics_binary_tree ] && extra=(--define R=0.2 --view 35,20)
  "$ontogen" run "models/$name.cell" --format png --size 360x360 --out "$scratch/top/$name" "${extra[@]}" 2>/dev/null
done
ffmpeg -v error -y -i "$scratch/top/flower/flower.png" -i "$scratch/top/orchard/orchard.png" \
  -i "$scratch/top/colony/colony.png" -i "$scratch/top/statics_binary_tree/statics_binary_tree.png" \
  -filter_complex hstack=inputs=4 docs/images/models.png

# The movies: the flower and the orchard growing, each a 4-second movie (101 frames,
# what a run that writes a movie gives by default), side by side; the walking creature.
"$ontogen" run models/flower.cell --format mp4 --size 360x360 --out "$scratch/grow" 2>/dev/null
"$ontogen" run models/orchard.cell --format mp4 --size 360x360 --out "$scratch/grow" 2>/dev/null
ffmpeg -v error -y -i "$scratch/grow/flower.mp4" -i "$scratch/grow/orchard.mp4" -filter_complex hstack=inputs=2 \
  -c:v libx264 -pix_fmt yuv420p -movflags +faststart docs/media/growth.mp4
"$ontogen" run models/creature.cell --define SEGMENTS=6 --define DUTY=0.5 --format mp4 --size 640x400 \
  --out "$scratch/creature" 2>/dev/null
cp "$scratch/creature/creature.mp4" docs/media/creature.mp4

# Under physics (the dynamics set, MuJoCo): the creature walking six cycles, and the
# sapling swaying in the gusts of models/windy_tree.cell.
"$ontogen" run models/creature.cell --interpret dynamics --define SEGMENTS=6 --define DUTY=0.5 --until 8.4 \
  --format png,mp4 --size 640x400 --out "$scratch/walker" 2>/dev/null
cp "$scratch/walker/creature.png" docs/images/creature_dynamics.png
cp "$scratch/walker/creature.mp4" docs/media/creature_dynamics.mp4
"$ontogen" run models/windy_tree.cell --format mp4 --size 400x400 --out "$scratch/tree" 2>/dev/null
cp "$scratch/tree/windy_tree.mp4" docs/media/windy_tree.mp4

# The gait bred under physics for distance (README.md gives the figures): ten generations
# of twelve, the body held, then the best walker's picture and movie.
"$ontogen" evolve models/creature.cell --interpret dynamics --measure FITNESS=distance \
  --define SEGMENTS=6 --define PERIOD=1.2 --define SEG_LEN=1.1 --define SEG_R=0.34 \
  --define UPPER=0.95 --define LOWER=1.15 --range DUTY=0.4:0.9 \
  --generations 10 --population 12 --evolve-seed 1 --no-progress --out "$scratch/evolution" >/dev/null 2>&1
"$ontogen" run "$scratch/evolution/best.cell" --interpret dynamics --until 6 --format png,mp4 --size 640x400 \
  --out "$scratch/evolved" 2>/dev/null
cp "$scratch/evolved/best.png" docs/images/evolved_walker.png
cp "$scratch/evolved/best.mp4" docs/media/evolved_walker.mp4
