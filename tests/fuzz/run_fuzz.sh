#!/usr/bin/env bash
# Runs one fuzz target as a test (tests/fuzz/CMakeLists.txt):
#   run_fuzz.sh PROGRAM TARGET WORKDIR SECONDS SOURCE_DIR ASSIMP_MODELS
# 1. every input in tests/fuzz/regressions/TARGET once (each found a bug once);
# 2. the seed corpus, then SECONDS of seeded fuzzing; new inputs go to WORKDIR/corpus (kept
#    between runs of the same build folder, so later runs start further on). A crash, a leak,
#    a sanitizer report or a hang (30 s for one input) fails the test; the input that did it is
#    in WORKDIR/ (crash-*, leak-*, timeout-*): copy it to tests/fuzz/regressions/TARGET/.
#    (30 s, not 10: the slowest input known to be legitimate, regressions/scene/chain-with-a-
#    5-m-link-18-s-for-three-steps, takes 4.5-9 s sanitized on an idle 2-core machine and 12 s
#    under ./dev.sh test's load, and once kept in the corpus it failed the 10 s limit at
#    random. A hang runs for ever, so the margin costs the check nothing.)
set -euo pipefail
program=$(realpath "$1") target=$2 work=$3 seconds=$4 src=$(realpath "$5") models=$6
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$work/corpus" "$work/seeds"
cd "$work"

# Seeds. Scenes: the samples and the test scenes. Meshes: the first byte picks the extension
# (fuzz_mesh.cpp: 0 .obj, 1 .stl, 2 .ply, 3 .off, 4 .glb), the rest is a file of that kind.
# Mesh data: the reader's answers for those meshes (fuzz_meshdata.cpp).
case "$target" in
  scene)
    cp "$src"/resources/scenes/*.json seeds/
    ;;
  mesh)
    i=0
    for f in "$src"/resources/meshes/* "$models"/OBJ/*.obj "$models"/STL/*.stl "$models"/PLY/*.ply \
             "$models"/OFF/*.off "$models"/glTF2/Box*-glTF-Binary/*.glb; do
      [ -f "$f" ] || continue
      [ "$(stat -c %s "$f")" -le 65536 ] || continue
      case "${f##*.}" in
        obj) b='\000' ;; stl) b='\001' ;; ply) b='\002' ;; off) b='\003' ;; glb) b='\004' ;; *) continue ;;
      esac
      { printf "$b"; cat "$f"; } > "seeds/$(printf %03d $i)-$(basename "$f")"
      i=$((i + 1))
    done
    ;;
  meshdata)
    # The answers of the reader's child for the same meshes (fuzz_meshdata.cpp writes them).
    list=
    for f in "$src"/resources/meshes/* "$models"/OBJ/*.obj "$models"/STL/*.stl "$models"/PLY/*.ply \
             "$models"/OFF/*.off; do
      [ -f "$f" ] && [ "$(stat -c %s "$f")" -le 65536 ] && list="$list:$f"
    done
    [ -n "$(ls seeds)" ] || TUMBLE_MAKE_SEEDS=seeds TUMBLE_SEED_MESHES="$list" "$program" 2>/dev/null
    ;;
  *) echo "run_fuzz.sh: unknown target $target" >&2; exit 2 ;;
esac

# Inputs assimp itself crashed or looped on (handled: the parent refuses them with a
# message) are kept here, to be added to the regressions.
mkdir -p reader-faults
export TUMBLE_FUZZ_KEEP="$PWD/reader-faults"

# Leaks inside libraries Tumble cannot fix are suppressed, each with its reason.
export LSAN_OPTIONS="suppressions=$here/lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}"

regressions="$here/regressions/$target"
if compgen -G "$regressions/*" >/dev/null; then
  echo "== $target: the regression inputs"
  "$program" -runs=0 "$regressions"
fi

echo "== $target: ${seconds} s of fuzzing from $(ls seeds | wc -l) seeds and $(ls corpus | wc -l) kept inputs"
exec "$program" -seed=1 -max_total_time="$seconds" -timeout=30 -rss_limit_mb=2048 -max_len=65536 \
  -print_final_stats=1 corpus seeds
