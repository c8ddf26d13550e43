#!/bin/sh
# The harness's own vcan check: a raw CAN socket receives every frame the J1939 feeder sends (good
# pairs and distractors), byte for byte and in order.
. /imucal/lib.sh
imucal-vm-can-receive --name vcan_raw_receive --interface vcan0 --frames "$OUT/raw-frames.csv" --idle-ms 1500 &
rx=$!
sleep 0.5
imucal-vm-j1939-feeder --interface vcan0 --scenario "$IMUCAL/scenario.csv" --frames "$OUT/raw-frames.csv" \
  --samples "$OUT/raw-samples.csv" --max-samples 200 || verdict vcan_feeder 0 "feeder exited $?"
wait "$rx"
