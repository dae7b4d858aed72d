#!/usr/bin/env bash
# Set up, build, and run Tumble or its tests on Debian 12.
#
#   ./dev.sh run [SCENE]   install what is missing, build, start the editor
#   ./dev.sh test          install what is missing, build, run every test (under Xvfb)
#   ./dev.sh build         install what is missing and build
#   ./dev.sh package       ... and make the Debian package, $BUILD_DIR/package/tumble_VERSION_ARCH.deb
#                          (lintian's report after it); install it with
#                          apt-get install ./$BUILD_DIR/package/tumble_*.deb
#   ./dev.sh sanitize      the engine, io, cli and fuzz tests built with clang, ASan and UBSan
#                          (part of `test`; a folder of its own, $BUILD_DIR-san), then the
#                          editor's (sanitize-ui)
#   ./dev.sh sanitize-ui   the editor's tests built with clang, ASan and UBSan, under Xvfb
#                          (not part of `test`: its cold build is ~10 min; $BUILD_DIR-san-ui)
#   ./dev.sh fuzz TARGET [SECONDS]   a long fuzz run of scene, mesh or meshdata (docs/reliability.md)
#   ./dev.sh faults [KILLS]          every write under faults, KILLS (20) kills a write
#
# Each step is skipped when it has nothing to do, so a second run is quick. Set
# BUILD_DIR to build elsewhere (default: build). Runs apt-get as root, or through sudo.
set -euo pipefail
cd "$(dirname "$0")"

BUILD_DIR=${BUILD_DIR:-build}
PACKAGES=(
  build-essential cmake ninja-build ccache pkg-config
  qt6-base-dev qt6-base-dev-tools qt6-qpa-plugins qt6-3d-dev qt6-charts-dev libqt6opengl6-dev libgl-dev libgl1-mesa-dri fonts-dejavu-core
  libeigen3-dev nlohmann-json3-dev libassimp-dev libqhull-dev
  assimp-testmodels
  libbullet-dev libode-dev libmujoco-dev
  xvfb xauth xdotool
  nodejs npm
  ffmpeg
  gnuplot-nox
  python3 blender python3-numpy
  slurm-wlm munge
  clang-14 libfuzzer-14-dev
  liblsan0
  help2man librsvg2-bin shared-mime-info lintian desktop-file-utils xdg-utils libfile-mimeinfo-perl strace
)
# ffmpeg is optional for users (the editor's MP4 export detects it at run time); the tests
# install it so that the video path is tested, not skipped. gnuplot draws tumble-bench's
# work-precision diagrams as PNGs (without it, only the .gp scripts are written). Blender
# reads the glTF exports in the blender/roundtrip test (its importer needs numpy). slurm-wlm
# and munge: cli/sweep_slurm starts a one-node Slurm cluster for `tumble sweep --slurm`.
# xdotool answers the real editor's recovery prompt in ui/recovery_e2e.
# help2man (the man page) and librsvg2-bin (the PNG icons) make the installed files
# (packaging/CMakeLists.txt); lintian, desktop-file-utils, xdg-utils with
# libfile-mimeinfo-perl, shared-mime-info and strace check the installed package
# (install/package: tests/install/install_test.py).

# The Khronos glTF validator for the export tests (tests/io/gltf_validator.h), from npm into
# the build folder; its 2.x releases are all "2.0.0-dev.3.N", which npm's "@2" does not match.
GLTF_VALIDATOR=gltf-validator@2.0.0-dev.3.10

install_missing() {
  local missing=() p
  for p in "${PACKAGES[@]}"; do
    # A nodejs from elsewhere (NodeSource) carries its own npm; Debian's would conflict.
    [ "$p" = npm ] && command -v npm >/dev/null && continue
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "dev.sh: installing ${missing[*]}"
  local sudo=()
  [ "$(id -u)" -eq 0 ] || sudo=(sudo)
  "${sudo[@]}" apt-get update -q
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}"
}

build() {
  if [ ! -f "$BUILD_DIR/build.ninja" ]; then
    cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Release
  fi
  cmake --build "$BUILD_DIR" -j2
}

# The sanitizer build: clang with AddressSanitizer, UndefinedBehaviorSanitizer (LeakSanitizer
# comes with ASan) and libFuzzer's coverage, without the editor; only what its tests need.
SAN_DIR=${BUILD_DIR}-san
# One sanitized tree: DIR, then its own cmake options.
build_sanitized_tree() {
  local dir=$1
  shift
  # Its objects carry debug lines (for the reports' stacks); ccache keys them by path relative
  # to the source folder, so a clean checkout elsewhere finds them in the cache.
  export CCACHE_BASEDIR=$PWD CCACHE_NOHASHDIR=1
  if [ ! -f "$dir/build.ninja" ]; then
    cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++-14 \
      -DTUMBLE_SANITIZE=ON -DTUMBLE_BUILD_BENCH=OFF "$@"
  fi
  cmake --build "$dir" -j2
}
build_sanitized() {
  build_sanitized_tree "$SAN_DIR" -DTUMBLE_FUZZ=ON -DTUMBLE_BUILD_UI=OFF
}
run_sanitized() {
  # Any report fails the test that caused it: ASan and LSan abort, UBSan is built not to
  # recover (-fno-sanitize-recover), and halt_on_error keeps that true for the runtime checks.
  # Sanitized physics runs 15-20 times slower than Release: the long stability runs take a
  # fifth of their simulated time there (TUMBLE_TEST_SHORT; the same code paths), and the
  # heaviest functions may still pass Qt Test's 5-minute limit.
  ASAN_OPTIONS=detect_leaks=1:halt_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1 \
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  QTEST_FUNCTION_TIMEOUT=1800000 TUMBLE_TEST_SHORT=1 \
    ctest --timeout 2400 --test-dir "$SAN_DIR" --output-on-failure -j2 -L 'engine|io|cli|fuzz' -LE 'soak|long' "$@"
}

# The editor under the same sanitizers (issue 19): Qt 3D draws through Mesa's llvmpipe under
# Xvfb. A folder of its own, since the editor and its Qt 3D headers make it the longest build.
# Leaks are not checked here: Qt 3D, the RHI plugin and Mesa keep allocations until exit, and
# the editor's own leaks are checked in the ordinary build (ui/soak_leaks, suppressions by
# library); ui/soak reads glibc's heap figures, which ASan replaces.
# The display xvfb-run gives the ui tests. -noreset: by default an X server resets when its
# last client leaves, and a client connecting during the reset is refused ("could not connect
# to display"): a test that kills every editor and starts a new one met it now and then (100
# of 300 quick reconnects failed without it, none with it).
XVFB_ARGS="-screen 0 1280x1024x24 -noreset"
SAN_UI_DIR=${BUILD_DIR}-san-ui
build_sanitized_ui() {
  build_sanitized_tree "$SAN_UI_DIR" -DTUMBLE_FUZZ=OFF -DTUMBLE_BUILD_UI=ON
}
run_sanitized_ui() {
  local run=(ctest --timeout 2400 --test-dir "$SAN_UI_DIR" --output-on-failure -j2 -L ui -LE soak "$@")
  [ -n "${DISPLAY:-}" ] || run=(xvfb-run -a -s "$XVFB_ARGS" "${run[@]}")
  ASAN_OPTIONS=detect_leaks=0:halt_on_error=1:detect_stack_use_after_return=1 \
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  QTEST_FUNCTION_TIMEOUT=1800000 TUMBLE_TEST_SHORT=1 \
    "${run[@]}"
}

# Once per build folder; a later run finds it there.
install_gltf_validator() {
  local dir="$BUILD_DIR/gltf-validator"
  grep -qs "\"version\": \"${GLTF_VALIDATOR#gltf-validator@}\"" "$dir/node_modules/gltf-validator/package.json" && return 0
  echo "dev.sh: installing $GLTF_VALIDATOR into $dir"
  mkdir -p "$dir"
  npm install --prefix "$dir" --no-audit --no-fund --no-save "$GLTF_VALIDATOR"
}

cmd=${1:-run}
[ $# -gt 0 ] && shift
case "$cmd" in
  run)
    install_missing
    build
    exec "$BUILD_DIR/app/tumble" "$@"
    ;;
  test)
    install_missing
    build
    install_gltf_validator
    # The ui tests need a display; xvfb-run gives them one when there is none.
    if [ -n "${DISPLAY:-}" ]; then
      ctest --test-dir "$BUILD_DIR" --output-on-failure -j2 "$@"
    else
      xvfb-run -a -s "$XVFB_ARGS" ctest --test-dir "$BUILD_DIR" --output-on-failure -j2 "$@"
    fi
    # The benchmark's smoke run (issue 8, docs/benchmarks.md): a reduced set in seconds. It
    # asserts no timing; it fails only on a crash, an exception or a non-finite state.
    bench_log="$BUILD_DIR/bench-quick.log"
    if "$BUILD_DIR/tests/bench/suite/tumble-bench" --quick --out "$BUILD_DIR/bench-quick" >"$bench_log" 2>&1; then
      tail -n 1 "$bench_log"
    else
      cat "$bench_log"
      echo "dev.sh: tumble-bench --quick failed" >&2
      exit 1
    fi
    build_sanitized
    BUILD_DIR=$SAN_DIR install_gltf_validator
    run_sanitized
    ;;
  sanitize)
    install_missing
    build_sanitized
    BUILD_DIR=$SAN_DIR install_gltf_validator
    run_sanitized "$@"
    build_sanitized_ui
    run_sanitized_ui
    ;;
  faults)
    # Every write under faults with 20 kills a write (./dev.sh test runs 5): issue 46,
    # docs/reliability.md "Every write under faults".
    install_missing
    build
    run=(env TUMBLE_FAULT_KILLS="${1:-20}" "$BUILD_DIR/tests/tst_ui_write_faults")
    [ -n "${DISPLAY:-}" ] || run=(xvfb-run -a -s "$XVFB_ARGS" "${run[@]}")
    exec "${run[@]}"
    ;;
  sanitize-ui)
    install_missing
    build_sanitized_ui
    run_sanitized_ui "$@"
    ;;
  fuzz)
    target=${1:?usage: $0 fuzz scene|mesh|meshdata [SECONDS]}
    install_missing
    build_sanitized
    exec tests/fuzz/run_fuzz.sh "$SAN_DIR/tests/fuzz/fuzz_$target" "$target" "$SAN_DIR/tests/fuzz/$target" \
      "${2:-3600}" "$PWD" /usr/share/assimp/models
    ;;
  build)
    install_missing
    build
    ;;
  package)
    install_missing
    build
    (cd "$BUILD_DIR" && cpack --config CPackConfig.cmake)
    deb=$(ls "$BUILD_DIR"/package/tumble_*.deb)
    echo "dev.sh: $deb; lintian says:"
    # (lintian fails on an error; its warnings and notes are shown.)
    lintian --tag-display-limit 0 --display-info "$deb" || { echo "dev.sh: lintian found errors in $deb" >&2; exit 1; }
    ;;
  *)
    echo "usage: $0 run [SCENE] | test [CTEST ARGS] | build | package | sanitize [CTEST ARGS] | sanitize-ui [CTEST ARGS] | fuzz TARGET [SECONDS] | faults [KILLS]" >&2
    exit 2
    ;;
esac
