#!/usr/bin/env bash
# Fuzzes every libFuzzer target of a sanitizer build (make test-sanitize builds them) for SECONDS
# each, seeded with fuzz/seeds/<target>/, the inputs kept from earlier findings
# (fuzz/regressions/<target>/), and every scene and mesh in the repository. A crash, leak,
# timeout (10 s per input) or out-of-memory (2 GB) stops the target, writes the input to
# fuzz/findings/<target>/ and makes this script fail; fix it, then keep the input in
# fuzz/regressions/<target>/ so that every sanitizer build replays it.
#   scripts/fuzz.sh [BUILD_DIR] [SECONDS]     (defaults: build-sanitize 60)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-build-sanitize}" && pwd)
seconds=${2:-60}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
status=0
for target in scene_loader set_override obj_reader tetgen_reader gmsh_reader; do
  corpus=$work/corpus_$target
  mkdir -p "$corpus" "$root/fuzz/findings/$target"
  cp "$root/fuzz/seeds/$target/"* "$corpus/"
  if [ -d "$root/fuzz/regressions/$target" ]; then cp "$root/fuzz/regressions/$target/"* "$corpus/"; fi
  case $target in
    scene_loader) cp "$root"/scenes/*.json "$corpus/" ;;  # (bench/scenes are benchmark-sized: seconds to build)
    obj_reader) cp "$root"/scenes/meshes/*.obj "$corpus/" ;;
  esac
  echo "== fuzz_$target: $seconds s"
  # Run from an empty directory: relative mesh paths in fuzzed scenes then point nowhere.
  if ! (cd "$work" && "$build/fuzz/fuzz_$target" "$corpus" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
        -max_len=65536 -print_final_stats=1 -artifact_prefix="$root/fuzz/findings/$target/" > "$work/log_$target" 2>&1); then
    status=1
    tail -n 60 "$work/log_$target"
  fi
  grep -E "^stat::number_of_executed_units|^stat::peak_rss_mb|^#[0-9]+.*DONE" "$work/log_$target" || true
done
exit $status
