#!/bin/sh
# The harness's own i2c-stub check for the LIS3MDL: little-endian X/Y/Z from 0x28 and from 0xA8 (the
# auto-increment address a driver may use).
. /imucal/lib.sh
imucal-vm-lis3mdl-feeder --bus "$(i2c_bus)" --address 0x1c --scenario "$IMUCAL/scenario.csv" \
  --written "$OUT/stub-lis.csv" --max-samples 300 --fs-gauss 4 &
feeder=$!
for reg in 0x28 0xa8; do
  imucal-vm-i2c-readback --name "stub_lis3mdl_readback_$reg" --bus "$(i2c_bus)" --address 0x1c --id-reg 0x0f --id-value 0x3d \
    --data-reg "$reg" --columns mx_raw,my_raw,mz_raw --endian little --written "$OUT/stub-lis.csv" --reads 100 --period-ms 7
done
wait "$feeder" || verdict stub_lis3mdl_feeder 0 "feeder exited $?"
