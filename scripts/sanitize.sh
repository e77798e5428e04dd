#!/usr/bin/env bash
# Builds revdist with sanitizers into its own build folder and runs tests there.
#   scripts/sanitize.sh address [ctest args]  -fsanitize=address,undefined, the default suite (-LE stress)
#   scripts/sanitize.sh thread  [ctest args]  -fsanitize=thread, the tests that run queries on several threads
# Not part of the default run (a sanitized build is 2-10x slower); CI may run it optionally.
set -euo pipefail
cd "$(dirname "$0")/.."
mode=${1:-address}
shift || true
case "$mode" in
  address) flags="address,undefined"; dir=build-asan; select=(-LE stress) ;;
  thread)  flags="thread";            dir=build-tsan; select=(-R 'Threads') ;;
  *) echo "usage: scripts/sanitize.sh address|thread [ctest args]" >&2; exit 2 ;;
esac
jobs=${JOBS:-$(nproc)}
cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=Release -DREVDIST_SANITIZE="$flags" -DREVDIST_BUILD_BENCHMARKS=OFF >/dev/null
if [ "$mode" = thread ]; then
  # Every test named *Threads* (queries and scene frames on several threads).
  cmake --build "$dir" -j"$jobs" --target solid_distance_threads_test scene_test
else
  cmake --build "$dir" -j"$jobs"
fi
# halt_on_error: a report fails the test; detect_leaks: the CLI tests run the binary too.
export ASAN_OPTIONS=${ASAN_OPTIONS:-halt_on_error=1:detect_leaks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1}
export TSAN_OPTIONS=${TSAN_OPTIONS:-halt_on_error=1}
ctest --test-dir "$dir" "${select[@]}" --output-on-failure -j"$jobs" --timeout 3000 "$@"
