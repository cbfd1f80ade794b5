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
# Each stage's heading with the time it starts, so that a CI log shows where the minutes go.
stage() { echo "== $* ($(date -u +%T))"; }

stage "Release build"
cmake -S . -B build "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DFINVERSE_WERROR=ON -DFINVERSE_SKIP_AREAS=
cmake --build build -j "$jobs"
stage "Debug + ASan/UBSan configure"
# -O1 keeps the sanitizers exact (ASan's own advice) and makes the sanitized tests several times
# faster than -O0. Warnings are errors only in the Release build. -g1 (line tables only) is all a
# sanitizer report needs for file:line stack frames; full -g made the objects 2.4x larger.
# clang, where installed (install-deps.sh installs it), compiles this build in about 0.65 of GCC's
# time; the Release build stays on GCC, Debian's own compiler (docs/studies/build_time.md).
# clang also compiles a target's files in batches of 64 instead of 16: its optimiser then works on
# each template instantiation once per 64 files (two of fem's batches together: 150 s -> 116 s);
# GCC gains nothing from larger batches (100 s -> 120 s), so the Release build keeps 16.
asan_compiler=()
if command -v clang++ >/dev/null; then
  asan_compiler=(-DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DFINVERSE_UNITY_BATCH=64)
fi
cmake -S . -B build-asan "${generator[@]}" "${asan_compiler[@]}" -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g1" \
  -DFINVERSE_SANITIZE=ON -DFINVERSE_WERROR=OFF -DFINVERSE_SKIP_AREAS=

stage "Release tests, the sanitized build beside them"
# The Release tests leave about a sixth of the cores idle (the workflow test's serial stages at
# the end); the sanitized build, at the lowest priority, takes what they leave. Only what the unit
# tests need: the sanitized build runs no other test. Its output goes to a log, shown on failure.
# Its own process group (set -m), to be stopped whole if the tests fail; not its own session
# (setsid): with the kernel's autogroups a session is scheduled as a whole, and nice would then
# count only inside it (measured: the workflow test ran at half speed beside a setsid build).
asan_log=build-asan/build.log
set -m
nice -n 19 cmake --build build-asan -j "$jobs" --target unit_tests > "$asan_log" 2>&1 &
asan_build=$!
set +m
trap 'kill -- -"$asan_build" 2>/dev/null || true' EXIT
ctest --test-dir build -j "$jobs" --output-on-failure --timeout 900
stage "Debug + ASan/UBSan build (finishing)"
if ! wait "$asan_build"; then
  tail -n 60 "$asan_log"
  echo "the sanitized build failed (whole log: $asan_log)"
  exit 1
fi
trap - EXIT
tail -n 1 "$asan_log"
stage "Debug + ASan/UBSan unit tests"
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
# The five slowest of the rest, 25-97 s each under the sanitizers (1-9 s in Release): the 3-D
# heaving sphere's cut-cell balance (its 2-D twin MovingBody.CutCellBalance* runs sanitized), the
# rigid-pitching plate as a closed body (the sheet variant runs sanitized), and three scans of
# the fin's eq. (2) objective (QuasiStaticObjective's other tests and fem's LinearIncrement.* run
# sanitized). Measured in docs/studies/build_time.md.
heavy+='|ImmersedFlow3D.CutCellBalanceSmoothsTheForceOfAHeavingSphere|PitchingPlateFsi.StiffPlateFollowsTheRigidPitching'
heavy+='|QuasiStaticObjective.SmallHeaveTwinWithLoadsIsClosestAtTheTruthScale'
heavy+='|QuasiStaticObjective.LinearIncrementFollowsNewtonOnTheFin|QuasiStaticObjective.WithoutLoadsTheModulusScaleIsNotIdentifiable'
# One process per test executable, not per test: each sanitized process costs 0.2-0.6 s of
# start-up and leak check, which over ~600 tests was most of two minutes (build_time.md).
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  /usr/bin/python3 tools/scripts/run_tests_per_executable.py --build build-asan --jobs "$jobs" --timeout 1800 \
  -- -L unit -E "$heavy"
stage "all tests passed"
