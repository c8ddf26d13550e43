#!/bin/sh
# imucal-j1939 on vcan0: the feeder sends the scenario as PGN 61482/61485 pairs from 0x80 (5 ms latency
# byte), with frames from 0x81, short, 11-bit, remote, other-PGN and not-available/error frames in
# between; every published sample must equal a good pair within one LSB (0.01 m/s^2, 1/128 deg/s), none
# may come from a distractor (they would not match), and the not-available pairs must not be published.
. /imucal/lib.sh
record can IMUCAL_IMU
# The feeder drops a sample it is too late for (as a sensor would never burst), so on a slow host fewer
# than the 360 good pairs go out (298 on one run): the driver stops at 200.
imucal-j1939 --config "$IMUCAL/vmconfigs/j1939.yaml" --lcm-url "$LCM_URL" --max-samples 200 --sensor-id imu0 \
  > "$OUT/j1939-driver.txt" 2>&1 &
driver=$!
sleep 1
imucal-vm-j1939-feeder --interface vcan0 --scenario "$IMUCAL/scenario.csv" --frames "$OUT/can-frames.csv" \
  --samples "$OUT/can-samples.csv" --max-samples 400
t0="$(uptime_s)"
rc=0
for i in $(seq 1 50); do kill -0 "$driver" 2>/dev/null || break; sleep 0.1; done
if kill -0 "$driver" 2>/dev/null; then kill -INT "$driver"; rc=124; fi
wait "$driver"; r=$?; [ "$rc" = 0 ] && rc=$r
cat "$OUT/j1939-driver.txt" | tail -3
good="$(($(wc -l < "$OUT/can-samples.csv") - 1))"
verdict j1939_driver_exit "$([ $rc = 0 ] && echo 1 || echo 0)" "exit $rc (--max-samples 200; $good good pairs sent)"
stop_recording
imucal-vm-lcm-check --name j1939_driver_samples --log "$OUT/can.lcmlog" --channel IMUCAL_IMU --kind imu \
  --expected "$OUT/can-samples.csv" --sensor-id imu0 --min-samples 200 --slack-ms 6 \
  --accel-lsb 0.01 --gyro-lsb-dps 0.0078125
