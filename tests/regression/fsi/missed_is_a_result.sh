#!/bin/sh
# Runs a validation command whose graded metrics may miss (exit 1: it ran to the end and wrote
# its files, rules/common.smk METRIC_MISSED_IS_A_RESULT); the regression test compares the files.
"$@"
rc=$?
[ "$rc" -eq 0 ] || [ "$rc" -eq 1 ]
