# Shared by the VM's check scripts (sourced): the verdict line, timing, and the i2c-stub bus.
uptime_s() { cut -d' ' -f1 /proc/uptime; }
log() { echo "VMLOG [$(uptime_s)] $*"; }
# verdict NAME OK(1|0) NUMBERS
verdict() {
  if [ "$2" = 1 ]; then echo "VMCHECK PASS $1: $3"; else echo "VMCHECK FAIL $1: $3"; fi
}
i2c_bus() { cat "$OUT/i2c-bus"; }
