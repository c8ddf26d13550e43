#!/usr/bin/env bash
# imucald as users run it, from its YAML configuration, inside a private network namespace (lo only):
#  1. bad messages published on the IMU channel (NaN, time going backwards, duplicates, out of range, a
#     foreign sensor id) and a heading source that stops mid-turn: each bad message is counted under its
#     reason, every good sample is accepted, and the calibration still matches the truth;
#  2. SIGHUP with a broken configuration: refused with file:line, the daemon runs on;
#  3. SIGHUP with a new configuration (sessions only on a trigger, another calibration channel): a
#     calibration turn without a trigger is not calibrated; after imucal-trigger the next one is.
#  The daemon is also paused (SIGSTOP) for 0.1 s a few times while samples flow, as a loaded machine's
#  scheduler or hypervisor does: on resume LCM's receive thread drains the socket in a burst, and every
#  sample must still be accepted (LCM's default queue of 30 per subscription dropped some).
# At 10x, data time runs ahead of the wall clock: each later stream starts its data time after the last
# one's (--epoch-offset), as a real sensor's would.
# Usage: daemon_robustness_e2e.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/private_netns.sh"
build="$1"; src="$2"; speed=10
mkdir -p "$tmp/state"
cp "$src/configs/paper-calibrate.yaml" "$tmp/"
fail() { echo "FAILED: $*"; echo "--- daemon log"; cat "$tmp/daemon.log"; exit 1; }
wait_log() {  # pattern, seconds
  for _ in $(seq $(( $2 * 10 ))); do grep -q -- "$1" "$tmp/daemon.log" && return 0; sleep 0.1; done
  return 1
}
write_config() {  # automatic, calibration channel
  cat > "$tmp/imucald.yaml" <<YAML
lcm_url: "$url"
state_dir: $tmp/state
sensors: [imu0]
channels:
  calibration: $2
session:
  automatic: $1
calibration_config: paper-calibrate.yaml
YAML
}

write_config true IMUCAL_CALIBRATION
"$build/daemon/imucald" --config "$tmp/imucald.yaml" > "$tmp/daemon.log" 2>&1 &
daemon=$!; pids+=("$daemon")

pause_daemon() {  # times, seconds each
  for _ in $(seq "$1"); do sleep 0.4; kill -STOP "$daemon"; sleep "$2"; kill -CONT "$daemon"; done
}

echo "== bad messages, a heading that stops at 12 s, a daemon paused 5 x 0.1 s: counted, rejected, calibration still right"
"$build/tests/imucal-cal-check" --lcm-url "$url" --truth "$tmp/truth1.json" --timeout 60 \
  --expect-report "$tmp/report1.json" &
check=$!; pids+=("$check")
"$build/sim/imucal-sim-pub" --config "$src/configs/paper-sim.yaml" --seed 11 --lcm-url "$url" --speed "$speed" \
  --truth "$tmp/truth1.json" --start-delay 2 --faults nan=3,backwards=2,duplicate=4,range=1,foreign=5,malformed=3 \
  --heading-until 12 --report "$tmp/report1.json" &
publisher=$!; pids+=("$publisher")
sleep 2.5
pause_daemon 5 0.1
wait "$publisher"
rc=0; wait "$check" || rc=$?
[ "$rc" -eq 0 ] || fail "calibration or counters under bad input ($rc)"
kill -0 "$daemon" || fail "the daemon died"
wait_log "heading on IMUCAL_HEADING stopped" 5 || fail "the stopped heading source was not reported"
echo "ok: the daemon reported the stopped heading source"

echo "== SIGHUP with a broken configuration: refused, the daemon runs on"
printf 'sensors: [imu0]\nsesion:\n  automatic: false\n' > "$tmp/imucald.yaml"
kill -HUP "$daemon"
wait_log "reload refused" 5 || fail "no refusal logged"
grep "reload refused" "$tmp/daemon.log" | grep -q "imucald.yaml:2: unknown key 'sesion'" || fail "the refusal does not name file:line:key"
kill -0 "$daemon" || fail "the daemon died on a bad configuration"
echo "ok: $(grep -o 'reload refused.*' "$tmp/daemon.log" | head -1)"

echo "== SIGHUP with triggered sessions on IMUCAL_CALIBRATION_B: no trigger, no session; trigger, session"
write_config false IMUCAL_CALIBRATION_B
kill -HUP "$daemon"
wait_log "reload: .* applied" 5 || fail "the new configuration was not applied"
"$build/tests/imucal-cal-check" --lcm-url "$url" --truth "$tmp/truth2.json" --timeout 8 \
  --channel IMUCAL_CALIBRATION_B --new &
check=$!; pids+=("$check")
"$build/sim/imucal-sim-pub" --config "$src/configs/paper-sim.yaml" --seed 12 --lcm-url "$url" --speed "$speed" --epoch-offset 40 \
  --truth "$tmp/truth2.json" --start-delay 1
rc=0; wait "$check" || rc=$?
[ "$rc" -eq 2 ] || fail "a session was calibrated without a trigger (check exit $rc, expected 2: none)"
echo "ok: no calibration without a trigger"
"$build/tests/imucal-cal-check" --lcm-url "$url" --truth "$tmp/truth3.json" --timeout 60 \
  --channel IMUCAL_CALIBRATION_B --new &
check=$!; pids+=("$check")
sleep 1
"$build/daemon/imucal-trigger" --lcm-url "$url" --sensor-id imu0 --requester robustness-test
wait_log "trigger from robustness-test" 5 || fail "the trigger was not received"
"$build/sim/imucal-sim-pub" --config "$src/configs/paper-sim.yaml" --seed 13 --lcm-url "$url" --speed "$speed" --epoch-offset 80 \
  --truth "$tmp/truth3.json" --start-delay 1
rc=0; wait "$check" || rc=$?
[ "$rc" -eq 0 ] || fail "the triggered session was not calibrated right ($rc)"
kill -TERM "$daemon"; rc=0; wait "$daemon" || rc=$?
[ "$rc" -eq 0 ] || fail "imucald exit status $rc on SIGTERM"
echo "robustness end to end: 4 passed, 0 failed"
