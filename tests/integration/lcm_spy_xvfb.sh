#!/usr/bin/env bash
# lcm-spy (through scripts/lcm-spy) on a virtual X display decodes every imucal message type: the simulator
# publisher, the daemon and imucal-trigger run in a private network namespace (lo only), a screenshot of
# lcm-spy's window is taken and read back with OCR, which must find each channel's row with its type.
# Usage: lcm_spy_xvfb.sh BUILD_DIR SOURCE_DIR OUT_PNG
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/private_netns.sh"
build="$1"; src="$2"; png="$3"
java_url="udpm://239.255.76.67:7667?ttl=0"  # lcm-spy's Java provider: no recv_buf_size
display=":$((90 + RANDOM % 100))"
Xvfb "$display" -screen 0 1400x900x24 -nolisten tcp > "$tmp/xvfb.log" 2>&1 &
pids+=("$!")
for _ in $(seq 50); do [ -e "/tmp/.X11-unix/X${display#:}" ] && break; sleep 0.1; done
DISPLAY="$display" IMUCAL_BUILD_DIR="$build" bash "$src/scripts/lcm-spy" --lcm-url="$java_url" > "$tmp/spy.log" 2>&1 &
pids+=("$!")
"$build/daemon/imucald" --lcm-url "$url" --calibration-config "$src/configs/paper-calibrate.yaml" > "$tmp/daemon.log" 2>&1 &
pids+=("$!")
sleep 4  # the JVM and Spy's window
"$build/daemon/imucal-trigger" --lcm-url "$url" --sensor-id imu0 --requester lcm-spy-test > /dev/null
"$build/sim/imucal-sim-pub" --config "$src/configs/paper-sim.yaml" --seed 3 --lcm-url "$url" --speed 10 --start-delay 0.5
"$build/daemon/imucal-trigger" --lcm-url "$url" --sensor-id imu0 --requester lcm-spy-test > /dev/null
sleep 2
mkdir -p "$(dirname "$png")"
window="$(DISPLAY="$display" xwininfo -root -tree | awk '/LCM Spy/ {print $1; exit}')"
[ -n "$window" ] || { echo "FAILED: no lcm-spy window"; cat "$tmp/spy.log"; exit 1; }
DISPLAY="$display" import -window "$window" "$png"
echo "screenshot: $png"
# OCR of the Channel and Type columns of the six channel rows below the header (their share of Spy's
# default window), upscaled (the table font is small) and thresholded so the grid lines vanish.
read -r w h < <(identify -format '%w %h\n' "$png")
crop="$((w * 41 / 100))x$((h * 19 / 100))+0+$((h * 3 / 100))"
convert "$png" -crop "$crop" +repage -colorspace Gray -resize 400% -threshold 55% "$tmp/ocr.png"
tesseract "$tmp/ocr.png" "$tmp/ocr" --psm 4 > /dev/null 2>&1
# OCR drops underscores and spaces now and then: compare letters and digits only, lower case, and find
# each channel's row (by the end of its name) with its type's name on it.
tr -cd '[:alnum:]\n' < "$tmp/ocr.txt" | tr '[:upper:]' '[:lower:]' > "$tmp/ocr.norm"
ok=0; bad=0
for pair in calibration:calibration_t heading:heading_sample_t imu:imu_sample_t progress:session_progress_t \
            status:daemon_status_t trigger:calibration_trigger_t; do
  channel="${pair%%:*}"; type="${pair#*:}"; want="$(echo "$type" | tr -d '_')"
  if grep -E "cal${channel}.{0,2}${want}" "$tmp/ocr.norm" > /dev/null; then  # the column rule may read as a letter
    echo "ok: lcm-spy decodes IMUCAL_${channel^^} as $type"; ok=$((ok + 1))
  else
    echo "FAILED: no IMUCAL_${channel^^} row with type $type"; bad=$((bad + 1))
  fi
done
if [ "$bad" -ne 0 ]; then echo "--- OCR text"; cat "$tmp/ocr.txt"; fi
echo "lcm-spy: $ok passed, $bad failed"
[ "$bad" -eq 0 ]
