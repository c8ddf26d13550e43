#!/bin/sh
# imucal-icm42688 on i2c-stub: the feeder plays the chip (until the driver has its 200 samples) (4 g / 250 dps, axis map x,-y,-z), the driver
# resets, configures and polls it and publishes on LCM; every published sample must equal a written
# one within 1 LSB (accel 4 g / 32768, gyro 250 dps / 32768, temperature 1 / 132.48 degC), and the
# registers the driver configured must hold the feeder's full scales.
. /imucal/lib.sh
cfg="$(config icm42688.yaml)"
record icm IMUCAL_IMU
imucal-vm-icm42688-feeder --bus "$(i2c_bus)" --address 0x68 --scenario "$IMUCAL/scenario.csv" --written "$OUT/drv-icm.csv" \
  --accel-fs-g 4 --gyro-fs-dps 250 --axis-map x,-y,-z --check-config &
feeder=$!
sleep 0.2
t0="$(uptime_s)"
timeout -s KILL 90 imucal-icm42688 --config "$cfg" --lcm-url "$LCM_URL" --max-samples 200 --sensor-id imu0
rc=$?
verdict icm42688_driver_exit "$([ $rc = 0 ] && echo 1 || echo 0)" "exit $rc after $(awk -v a="$t0" -v b="$(uptime_s)" 'BEGIN {printf "%.1f", b - a}') s for --max-samples 200"
kill -TERM "$feeder"; wait "$feeder"
stop_recording
imucal-vm-lcm-check --name icm42688_driver_samples --log "$OUT/icm.lcmlog" --channel IMUCAL_IMU --kind imu \
  --expected "$OUT/drv-icm.csv" --sensor-id imu0 --min-samples 200 \
  --accel-lsb-g "$(awk 'BEGIN {printf "%.12g", 4 / 32768}')" \
  --gyro-lsb-dps "$(awk 'BEGIN {printf "%.12g", 250 / 32768}')" \
  --temp-lsb "$(awk 'BEGIN {printf "%.12g", 1 / 132.48}')"
