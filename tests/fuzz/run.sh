#!/bin/sh
# Runs each libFuzzer target for SECONDS from the committed corpus (new inputs go to build-fuzz/corpus-*), prints
# executions and coverage, and fails on any crash or contract violation. Usage: run.sh BUILD_DIR SECONDS
set -u
dir=$1
secs=$2
status=0
for t in fuzz_api fuzz_cli fuzz_surface; do
    mkdir -p "$dir/corpus-$t" "$dir/artifacts"
    log="$dir/$t.log"
    if "$dir/$t" -max_total_time="$secs" -print_final_stats=1 -artifact_prefix="$dir/artifacts/" \
        "$dir/corpus-$t" "tests/fuzz/corpus/$t" > "$log" 2>&1; then
        runs=$(grep -E '^stat::number_of_executed_units' "$log" | tail -1 | awk '{print $2}')
        cov=$(grep -E '^#[0-9]+' "$log" | tail -1 | sed -n 's/.*cov: \([0-9]*\) ft: \([0-9]*\).*/cov \1, ft \2/p')
        echo "$t: $runs executions in ${secs} s, $cov"
    else
        echo "$t: FAILED (see $log)"
        grep -E 'contract violated|ERROR|SUMMARY|Test unit written' "$log" | head -5
        status=1
    fi
done
exit $status
