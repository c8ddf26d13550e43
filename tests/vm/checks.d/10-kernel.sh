#!/bin/sh
# Debian's modules load, vcan0 comes up, lo carries multicast, and i2c-stub answers at both addresses.
. /imucal/lib.sh
ok=1
# i2c-stub: ICM-42688-P at 0x68 (REG_BANK_SEL 0x76 selects banks 1-4 over 0x00..0x10, where bank 0
# has nothing: the data, WHO_AM_I and DEVICE_CONFIG stay unbanked), LIS3MDL at 0x1c. dyndbg=+p turns on
# its trace of every transfer: the feeders read it to emulate clear-on-read status bits.
modprobe i2c-stub chip_addr=0x68,0x1c bank_reg=0x76 bank_mask=0x07 bank_start=0x00 bank_end=0x10 dyndbg=+p || ok=0
modprobe i2c-dev || ok=0
modprobe vcan || ok=0
modprobe can-raw || ok=0
mods="$(lsmod | awk 'NR > 1 {print $1}' | sort | tr '\n' ' ')"
for m in i2c_stub i2c_dev vcan can_raw can can_dev; do
  echo " $mods" | grep -q " $m " || { echo "module $m not loaded"; ok=0; }
done
ip link add dev vcan0 type vcan || ok=0
ip link set up vcan0 || ok=0
ip link set lo up || ok=0
ip route add 224.0.0.0/4 dev lo || ok=0
vcan="$(cat /sys/class/net/vcan0/operstate 2>/dev/null) mtu $(cat /sys/class/net/vcan0/mtu 2>/dev/null)"
bus=""
for d in /sys/class/i2c-dev/i2c-*; do
  [ "$(cat "$d/device/name" 2>/dev/null || cat "$d/name")" = "SMBus stub driver" ] && bus="/dev/$(basename "$d")"
done
[ -c "$bus" ] || { echo "no i2c-dev node for the stub"; ok=0; }
echo "$bus" > "$OUT/i2c-bus"
ifaces="$(ls /sys/class/net | tr '\n' ' ')"
verdict kernel_modules "$ok" "loaded: $mods; vcan0 $vcan; interfaces: $ifaces; i2c-stub on $bus"
