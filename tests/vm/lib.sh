# Shared by the VM's check scripts (sourced): the verdict line, timing, and the i2c-stub bus.
uptime_s() { cut -d' ' -f1 /proc/uptime; }
log() { echo "VMLOG [$(uptime_s)] $*"; }
# verdict NAME OK(1|0) NUMBERS
verdict() {
  if [ "$2" = 1 ]; then echo "VMCHECK PASS $1: $3"; else echo "VMCHECK FAIL $1: $3"; fi
}
i2c_bus() { cat "$OUT/i2c-bus"; }
# LCM inside the VM: multicast on lo (the VM has no other network interface at all).
LCM_URL="udpm://239.255.76.67:7667?ttl=0"
# record NAME CHANNELS: lcm-logger in the background; stop_recording waits until it has flushed.
record() {
  lcm-logger --lcm-url "$LCM_URL" -c "$2" -f "$OUT/$1.lcmlog" > "$OUT/$1.logger.txt" 2>&1 &
  RECORDER=$!
  sleep 0.5
}
stop_recording() {
  sleep 0.3
  kill -INT "$RECORDER" 2>/dev/null
  wait "$RECORDER" 2>/dev/null
}
# config TEMPLATE OUT: a driver config from tests/vm/configs with the stub's bus filled in.
config() { sed "s|@BUS@|$(i2c_bus)|" "$IMUCAL/vmconfigs/$1" > "$OUT/$1"; echo "$OUT/$1"; }
