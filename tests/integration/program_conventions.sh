#!/usr/bin/env bash
# Every program keeps the command-line conventions (imucal_app): `--version` prints "<program> <version>"
# and exits 0, `--help` exits 0, an unknown flag or a bad --log-level exits 2 naming it; `imucal calibrat`
# names the subcommand and the nearest one; imucal-trigger with no daemon (memq://: in-process, no
# network) says so and exits 1, in the journal's format when its stderr is the "journal".
# Usage: program_conventions.sh VERSION PROGRAM...
set -uo pipefail
version="$1"
shift
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
failed=0
fail() { echo "FAILED: $*"; failed=1; }

# expect STATUS PATTERN -- COMMAND...: the exit status and a fixed string in its stderr
expect() {
  local want="$1" pattern="$2"
  shift 3
  "$@" > "$tmp/out" 2> "$tmp/err"
  local rc=$?
  [ "$rc" -eq "$want" ] || fail "$(basename "$1") ${*:2}: exit $rc, expected $want; stderr: $(cat "$tmp/err")"
  grep -qF -- "$pattern" "$tmp/err" || fail "$(basename "$1") ${*:2}: stderr lacks '$pattern': $(cat "$tmp/err")"
}

for prog in "$@"; do
  name="$(basename "$prog")"
  out="$("$prog" --version)"
  rc=$?
  [ "$rc" -eq 0 ] && [ "$out" = "$name $version" ] || fail "$name --version: exit $rc, '$out' (expected '$name $version')"
  "$prog" --help > "$tmp/help" 2>&1 || fail "$name --help: exit $?"
  grep -q -- "--log-level" "$tmp/help" || fail "$name --help does not list --log-level"
  expect 2 "$name: unknown flag '--no-such-flag'" -- "$prog" --no-such-flag
  expect 2 "--log-level: loud not in" -- "$prog" --log-level loud
  echo "ok: $out"
done

for prog in "$@"; do
  case "$(basename "$prog")" in
    imucal)
      expect 2 "imucal: unknown subcommand 'calibrat' (did you mean 'calibrate'?)" -- "$prog" calibrat --imu x.csv
      expect 2 "imucal: unknown flag '--imus' (did you mean '--imu'?)" -- "$prog" calibrate --imus x.csv
      ;;
    imucal-trigger)
      expect 1 "error imucal-trigger: no imucald answered on IMUCAL_STATUS within 0.3 s" -- \
        "$prog" --lcm-url memq:// --timeout 0.3
      # What systemd sets for a service whose stderr is the journal: the stream's device and inode.
      : > "$tmp/journal"
      JOURNAL_STREAM="$(stat -c '%d:%i' "$tmp/journal")" "$prog" --lcm-url memq:// --timeout 0.3 2>> "$tmp/journal"
      line="$(cat "$tmp/journal")"
      [ "$line" = "<3>no imucald answered on IMUCAL_STATUS within 0.3 s" ] || fail "journald line: '$line'"
      echo "ok: journald: $line"
      ;;
  esac
done
exit "$failed"
