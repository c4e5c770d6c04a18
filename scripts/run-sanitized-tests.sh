#!/usr/bin/env bash
# Builds relight with AddressSanitizer and UndefinedBehaviorSanitizer (-DRELIGHT_SANITIZE=ON,
# RelWithDebInfo) into ./build-sanitize and runs the test suite under them, less the tests
# labelled `long` (tests/CMakeLists.txt says which and why; the plain suite runs them).
# Undefined behaviour, a memory error or a leak fails the test that met it. Leaks in code
# that is not the project's are suppressed in tests/sanitizers/lsan.supp, each with its
# reason.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRELIGHT_SANITIZE=ON \
    -DRELIGHT_WERROR=ON -DRELIGHT_BUILD_BENCH=OFF >/dev/null
cmake --build build-sanitize -j"$(nproc)"
export ASAN_OPTIONS=detect_leaks=1
export LSAN_OPTIONS=suppressions=$PWD/tests/sanitizers/lsan.supp:print_suppressions=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
cd build-sanitize
ctest --output-on-failure -j"$(nproc)" -LE long
