#!/usr/bin/env bash
# Runs each cargo-fuzz target until its fuzzer process has used SECONDS of CPU time (not wall
# time: on a shared machine libFuzzer's -max_total_time undercounts the work done), at low
# priority, and prints the executions, coverage and peak memory of each run.
#
#   scripts/fuzz-cpu.sh SECONDS [TARGET ...]     (from the repository root; needs nightly)
#
# A crash, leak, timeout or out-of-memory stops the script with the fuzzer's exit status; the
# input is in fuzz/artifacts/TARGET. New corpus entries go to fuzz/corpus/TARGET (not committed).
set -euo pipefail
cd "$(dirname "$0")/../fuzz"
seconds=${1:?usage: scripts/fuzz-cpu.sh SECONDS [TARGET ...]}
shift
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  mapfile -t targets < <(ls fuzz_targets | sed 's/\.rs$//')
fi
flags=(-rss_limit_mb=2048 -timeout=10 -print_final_stats=1)
cargo +nightly fuzz build -O
bin_dir=target/x86_64-unknown-linux-gnu/release

# CPU seconds used by a process so far.
cpu_of() { ps -o times= -p "$1" 2>/dev/null | tr -d ' ' || echo 0; }

for t in "${targets[@]}"; do
  mkdir -p "corpus/$t" "artifacts/$t"
  log=$(mktemp)
  nice -n 19 "$bin_dir/$t" "corpus/$t" "seeds/$t" "${flags[@]}" \
    -artifact_prefix="artifacts/$t/" >"$log" 2>&1 &
  pid=$!
  while kill -0 "$pid" 2>/dev/null; do
    used=$(cpu_of "$pid")
    if [ "${used:-0}" -ge "$seconds" ]; then kill -INT "$pid"; break; fi
    sleep 5
  done
  status=0
  wait "$pid" || status=$?
  execs=$(grep -E '^stat::number_of_executed_units' "$log" | awk '{print $2}')
  peak=$(grep -E '^stat::peak_rss_mb' "$log" | awk '{print $2}')
  cov=$(grep -oE 'cov: [0-9]+' "$log" | tail -1 | awk '{print $2}')
  echo "fuzz $t: ${used:-?} CPU s, ${execs:-?} executions, coverage ${cov:-?} edges, peak ${peak:-?} MB"
  # libFuzzer exits 0 or 72 (interrupted) when stopped by SIGINT; anything else is a finding.
  if [ "$status" -ne 0 ] && [ "$status" -ne 72 ] && [ "$status" -ne 130 ]; then
    grep -E 'ERROR|panicked|SUMMARY|Test unit written' "$log" >&2 || true
    echo "fuzz $t failed (exit $status): see fuzz/artifacts/$t" >&2
    exit "$status"
  fi
  rm -f "$log"
done
