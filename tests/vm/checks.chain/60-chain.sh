#!/bin/sh
# The whole chain on the real kernel: feeders play the paper motion (30 s, real time) on i2c-stub ->
# imucal-icm42688 + imucal-lis3mdl -> LCM on lo -> imucald -> imucal-cal-check, which compares the
# converged calibration with the simulator's truth (every bias within 4 sigma).
. /imucal/lib.sh
cfg_imu="$(config icm42688.yaml)"
cfg_mag="$(config lis3mdl.yaml)"
mkdir -p "$OUT/state"
imucald --lcm-url "$LCM_URL" --state-dir "$OUT/state" --calibration-config "$IMUCAL/configs/paper-calibrate.yaml" > "$OUT/chain-imucald.txt" 2>&1 &
daemon=$!
imucal-cal-check --lcm-url "$LCM_URL" --truth "$IMUCAL/truth.json" --timeout 150 > "$OUT/chain-cal-check.txt" 2>&1 &
check=$!
record chain 'IMUCAL_.*'
imucal-vm-icm42688-feeder --bus "$(i2c_bus)" --address 0x68 --scenario "$IMUCAL/scenario.csv" --written "$OUT/chain-icm.csv" \
  --accel-fs-g 4 --gyro-fs-dps 250 --axis-map x,-y,-z --hold-ms 2000 --linger-ms 500 > "$OUT/chain-icm-feeder.txt" 2>&1 &
imu_feeder=$!
imucal-vm-lis3mdl-feeder --bus "$(i2c_bus)" --address 0x1c --scenario "$IMUCAL/scenario.csv" --written "$OUT/chain-lis.csv" \
  --rate 80 --fs-gauss 4 --axis-map x,-y,-z --hold-ms 2000 --linger-ms 500 > "$OUT/chain-lis-feeder.txt" 2>&1 &
mag_feeder=$!
sleep 0.2
imucal-icm42688 --config "$cfg_imu" --lcm-url "$LCM_URL" --sensor-id imu0 > "$OUT/chain-icm-driver.txt" 2>&1 &
imu_driver=$!
imucal-lis3mdl --config "$cfg_mag" --lcm-url "$LCM_URL" --sensor-id imu0 > "$OUT/chain-lis-driver.txt" 2>&1 &
mag_driver=$!
t0="$(uptime_s)"
wait "$imu_feeder"; wait "$mag_feeder"
log "feeders done after $(awk -v a="$t0" -v b="$(uptime_s)" 'BEGIN {printf "%.1f", b - a}') s"
rc=0
wait "$check" || rc=$?
t1="$(uptime_s)"
kill -INT "$imu_driver" "$mag_driver" "$daemon" 2>/dev/null
wait "$imu_driver" "$mag_driver" "$daemon" 2>/dev/null
stop_recording
cat "$OUT/chain-icm-feeder.txt" "$OUT/chain-lis-feeder.txt"
tail -n 2 "$OUT/chain-icm-driver.txt" "$OUT/chain-lis-driver.txt"
cat "$OUT/chain-cal-check.txt"
imucal-vm-lcm-check --name chain_imu_samples --log "$OUT/chain.lcmlog" --channel IMUCAL_IMU --kind imu \
  --expected "$OUT/chain-icm.csv" --sensor-id imu0 --min-samples 2900 \
  --accel-lsb-g "$(awk 'BEGIN {printf "%.12g", 4 / 32768}')" \
  --gyro-lsb-dps "$(awk 'BEGIN {printf "%.12g", 250 / 32768}')"
imucal-vm-lcm-check --name chain_headings --log "$OUT/chain.lcmlog" --channel IMUCAL_HEADING --kind heading \
  --expected "$OUT/chain-lis.csv" --min-samples 2300 --heading-tol-deg 0.25
verdict chain_calibration "$([ $rc = 0 ] && echo 1 || echo 0)" \
  "imucal-cal-check exit $rc, $(awk -v a="$t0" -v b="$t1" 'BEGIN {printf "%.1f", b - a}') s from the drivers' start; $(grep -E 'calibration \(' "$OUT/chain-cal-check.txt" | head -1)"
