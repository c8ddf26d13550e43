#!/bin/busybox sh
# /init of the real-kernel test VM (busybox-static). Loads vcan, can-raw, i2c-stub and i2c-dev from
# Debian's kernel, brings up vcan0 and lo, runs every check in /imucal/checks.d in order, and reports:
# each check prints "VMCHECK PASS|FAIL name: numbers" on the serial console; at the end one
# "VMTEST RESULT PASS|FAIL" line, and qemu exits through isa-debug-exit (0x20 -> 65 pass, 0x01 -> 3 fail).
/bin/busybox --install -s /bin
export PATH=/imucal/bin:/bin
mount -t devtmpfs dev /dev
mount -t proc proc /proc
mount -t sysfs sys /sys
mount -t tmpfs tmp /tmp
export IMUCAL=/imucal OUT=/tmp/out
mkdir -p "$OUT"
failed=0
passed=0

uptime_s() { cut -d' ' -f1 /proc/uptime; }
log() { echo "VMLOG [$(uptime_s)] $*"; }
finish() {
  log "checks done: $passed passed, $failed failed"
  # imucal.dump=1 (IMUCAL_VM_DUMP=1 on the host): every log and recording, for run-vm-test.sh to unpack.
  if grep -q 'imucal.dump=1' /proc/cmdline; then
    echo "VMDUMP BEGIN"
    tar czf - -C /tmp out | base64
    echo "VMDUMP END"
  fi
  if [ "$failed" -eq 0 ] && [ "$passed" -gt 0 ]; then
    echo "VMTEST RESULT PASS"
    printf '\040' | dd of=/dev/port bs=1 seek=244 count=1 2>/dev/null
  else
    echo "VMTEST RESULT FAIL"
    printf '\001' | dd of=/dev/port bs=1 seek=244 count=1 2>/dev/null
  fi
  poweroff -f
}
log "userspace up, kernel $(uname -r)"
# Every check's verdict lines are counted from its output, so a check that dies silently still fails.
run_check() {
  file="$1"
  name="$(basename "$file" .sh)"
  t0="$(uptime_s)"
  log "check $name: start"
  "$file" > "$OUT/$name.log" 2>&1
  rc=$?
  cat "$OUT/$name.log"
  p=$(grep -c '^VMCHECK PASS' "$OUT/$name.log")
  f=$(grep -c '^VMCHECK FAIL' "$OUT/$name.log")
  if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then
    echo "VMCHECK FAIL $name: exited $rc without a verdict"
    f=1
  fi
  if [ "$p" -eq 0 ] && [ "$f" -eq 0 ]; then
    echo "VMCHECK FAIL $name: no verdict"
    f=1
  fi
  passed=$((passed + p))
  failed=$((failed + f))
  log "check $name: done in $(awk -v a="$t0" -v b="$(uptime_s)" 'BEGIN {printf "%.1f", b - a}') s"
}

for c in /imucal/checks.d/*.sh; do run_check "$c"; done
finish
