#!/bin/sh
# The harness's own i2c-stub check for the ICM-42688-P: the feeder writes 300 samples at 100 Hz, an
# independent SMBus reader reads the burst back (0x1D..0x2D) and finds each read among the written samples;
# polled faster than the ODR, DATA_RDY must announce each sample once (the clear-on-read emulation).
. /imucal/lib.sh
imucal-vm-icm42688-feeder --bus "$(i2c_bus)" --address 0x68 --scenario "$IMUCAL/scenario.csv" \
  --written "$OUT/stub-icm.csv" --max-samples 300 --accel-fs-g 2 --gyro-fs-dps 250 &
feeder=$!
imucal-vm-i2c-readback --name stub_icm42688_readback --bus "$(i2c_bus)" --address 0x68 --id-reg 0x75 --id-value 0x47 \
  --data-reg 0x1d --columns temp_raw,ax_raw,ay_raw,az_raw,gx_raw,gy_raw,gz_raw --endian big \
  --written "$OUT/stub-icm.csv" --reads 200 --period-ms 4 --status-reg 0x2d --status-bit 3
wait "$feeder" || verdict stub_icm42688_feeder 0 "feeder exited $?"
