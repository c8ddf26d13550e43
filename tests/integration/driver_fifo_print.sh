#!/usr/bin/env bash
# imucal-icm42688-emulated reading the FIFO, in one process on in-process LCM (memq://: nothing leaves the
# process, so no network namespace is needed): --print gives one line per sample, the samples are 10 ms
# apart with consecutive sequence numbers, and the exit counters show about one FIFO read per 10 samples.
# Usage: driver_fifo_print.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build="$1"; src="$2"
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
"$build/drivers/imucal-icm42688-emulated" --config "$src/drivers/configs/emulated-icm42688-fifo.yaml" --seed 3 \
  --lcm-url memq:// --max-samples 55 --print > "$tmp/out.csv" 2> "$tmp/log"
cat "$tmp/log"
# Within a batch the times step by the records' own stamps (exactly 10 ms here); a batch whose edge was
# read late (a loaded machine) is stamped with its read time, so the steps between batches may differ by
# any amount: only their order is checked, nothing that depends on how fast this machine is.
awk -F, '
  $1 != "imu" { print "not an imu line: " $0; bad = 1 }
  NR > 1 && $3 != seq + 1 { print "line " NR ": seq " $3 " after " seq; bad = 1 }
  NR > 1 && $2 - t <= 0 { print "line " NR ": " ($2 - t) " us after the previous sample"; bad = 1 }
  NR > 1 && $2 - t == 10000 { exact++ }
  { seq = $3; t = $2; n++ }
  END {
    if (n != 55) { print n " lines, expected 55"; bad = 1 }
    if (exact < 45) { print "only " exact " of 54 steps are 10 ms"; bad = 1 }
    exit bad
  }' "$tmp/out.csv"
grep -q "as imu_batch_t (FIFO, watermark 10 samples)" "$tmp/log" || { echo "not in FIFO mode"; exit 1; }
grep -q "after 55 samples" "$tmp/log" || { echo "did not stop after 55 published samples"; exit 1; }
grep -qE "counters at exit: .* fifo_overflow=0 fifo_bad_count=0 fifo_bad_header=0 " "$tmp/log" \
  || { echo "unexpected counters"; exit 1; }
# One FIFO read per watermark of 10 (a late read finds more): 55 samples in at most 8 reads, not 55.
reads="$(sed -nE 's/.*counters at exit: .* fifo_reads=([0-9]+) .*/\1/p' "$tmp/log")"
[ -n "$reads" ] && [ "$reads" -ge 1 ] && [ "$reads" -le 8 ] || { echo "fifo_reads=$reads, expected 1..8"; exit 1; }
echo "driver FIFO print: passed"
