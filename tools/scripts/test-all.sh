#!/usr/bin/env bash
# Builds finverse twice and runs every test in both builds:
#   build/       Release, warnings as errors: unit, regression (fin-diff golden files), workflow
#   build-asan/  Debug with AddressSanitizer + UndefinedBehaviorSanitizer: the unit tests
# This is what .ci/run runs. Jobs default to the machine's cores (CI has 2).
set -euo pipefail
cd "$(dirname "$0")/../.."
jobs=${JOBS:-$(nproc)}
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)

echo "== Release build"
cmake -S . -B build "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DFINVERSE_WERROR=ON -DFINVERSE_SKIP_AREAS=
cmake --build build -j "$jobs"
echo "== Release tests"
ctest --test-dir build -j "$jobs" --output-on-failure --timeout 900

echo "== Debug + ASan/UBSan build"
# -O1 keeps the sanitizers exact (ASan's own advice) and makes the sanitized tests several times
# faster than -O0. Warnings are errors only in the Release build: with sanitizer instrumentation
# GCC 12 reports -Wmaybe-uninitialized inside libstdc++'s <regex>, a false positive. -g1 (line
# tables only) is all a sanitizer report needs for file:line stack frames; full -g debug info
# made the objects 2.4x larger and the compile and link of this stage slower.
cmake -S . -B build-asan "${generator[@]}" -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g1" -DFINVERSE_SANITIZE=ON -DFINVERSE_WERROR=OFF -DFINVERSE_SKIP_AREAS=
# Only what the unit tests need: the sanitized build runs no other test.
cmake --build build-asan -j "$jobs" --target unit_tests
echo "== Debug + ASan/UBSan unit tests"
# Tests that repeat a code path many times over (objective scans, short fits, a noise run, a whole
# fin-track run, a 48-pose calibration) take 10-90 s each under the sanitizers; their code paths run
# in the quicker tests of the same suites, and they themselves run in the Release stage above.
heavy='DynamicObjective.VanishesAtTheTruth|UniformPlateTwin.ObjectiveVanishes|UniformPlateFit.AShortFit'
heavy+='|FinLoadNoise.ATranslatingTwoCellPlate|Objectives.EvaluationTimes'
heavy+='|FinTrackFitQuality.ASingleViewExitsOneWithItsReasonAndAFlaggedRecord'
heavy+='|CheckerboardCalibration.SimulatedRecordingGivesBackTheRig'
# Variants of FinFsi.SmallFinRunsAndTheRootFollowsTheDrive (the same coupled fin step, 24-41 s
# each under the sanitizers): a tracked drive and planted effects.
heavy+='|FinFsi.TrackedRootMotionDrivesTheFin|FinFsi.EffectsAreAppliedToTheStructureAndRecorded'
# Four small-fin runs (closed and sheet, each whole and restarted; the restart path itself runs
# sanitized in FsiCheckpoint.*), and the 3-D towed sphere of the case-file motion (its 2-D
# neighbours run sanitized).
heavy+='|FinFsi.RestartFromACheckpointContinuesBitForBit|MovingCaseFile.TowedSphereFeelsTheForceOfTheFixedOne'
# One process per test executable, not per test: each sanitized process costs 0.2-0.6 s of
# start-up and leak check, which over ~600 tests was most of two minutes (build_time.md).
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  /usr/bin/python3 tools/scripts/run_tests_per_executable.py --build build-asan --jobs "$jobs" --timeout 1800 \
  -- -L unit -E "$heavy"
echo "== all tests passed"
