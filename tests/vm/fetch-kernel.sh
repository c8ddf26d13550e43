#!/usr/bin/env bash
# Fetches Debian's kernel for the real-kernel test (the .deb only: it is never installed on the host),
# pinned to the package linux-image-amd64's candidate depends on, and unpacks what the VM needs into
# CACHE/<package>: vmlinux (ELF, for qemu's PVH boot), the modules the test loads with their
# dependencies, and their kernel version. Cached: a second run does nothing. Prints the directory.
# Usage: fetch-kernel.sh [CACHE]   (default $IMUCAL_VM_CACHE, else /var/cache/imucal-vm as root)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
default_cache=/var/cache/imucal-vm
[ "$(id -u)" -eq 0 ] || default_cache="${XDG_CACHE_HOME:-$HOME/.cache}/imucal-vm"
cache="${1:-${IMUCAL_VM_CACHE:-$default_cache}}"
modules=(vcan can-raw i2c-stub i2c-dev)   # can, can-dev come as dependencies
fail() { echo "fetch-kernel: $*" >&2; exit 1; }

candidate() { apt-cache policy linux-image-amd64 2>/dev/null | awk '/Candidate:/ {print $2}'; }
cand="$(candidate)"
if [ -z "$cand" ] || [ "$cand" = "(none)" ]; then
  apt-get update -qq >&2 || true
  cand="$(candidate)"
fi
[ -n "$cand" ] && [ "$cand" != "(none)" ] || fail "apt has no candidate for linux-image-amd64 (is Debian's main archive in sources.list?)"
pkg="$(apt-cache depends "linux-image-amd64=$cand" | awk '$1 == "Depends:" && $2 ~ /^linux-image-[0-9]/ {print $2; exit}')"
[ -n "$pkg" ] || fail "linux-image-amd64 $cand depends on no linux-image-<version> package"
dir="$cache/$pkg"
if [ -f "$dir/ready" ]; then echo "$dir"; exit 0; fi

mkdir -p "$cache"
work="$(mktemp -d "$cache/.fetch.XXXXXX")"
trap 'rm -rf "$work"' EXIT
(cd "$work" && apt-get download -q -o APT::Sandbox::User=root "$pkg" >&2) || fail "apt-get download $pkg failed"
deb="$(ls "$work"/*.deb)"
dpkg-deb -x "$deb" "$work/x"
kver="$(ls "$work/x/lib/modules")"
mkdir -p "$work/out/modules"
"$here/extract-vmlinux.sh" "$work/x/boot/vmlinuz-$kver" "$work/out/vmlinux"
cp "$work/x/boot/config-$kver" "$work/out/config"

# Modules and their dependencies (the .modinfo "depends=" field; the .deb ships no modules.dep).
moddir="$work/x/lib/modules/$kver/kernel"
declare -A seen=()
add_module() {
  local name="$1" file
  [ -n "${seen[$name]:-}" ] && return 0
  file="$(find "$moddir" -name "$name.ko*" -o -name "${name//-/_}.ko*" | head -1)"
  [ -n "$file" ] || fail "$pkg has no module $name (built in? check $work/out/config)"
  seen[$name]=1
  local rel="${file#"$moddir"/}"
  mkdir -p "$work/out/modules/kernel/$(dirname "$rel")"
  case "$file" in
    *.ko)    cp "$file" "$work/out/modules/kernel/$rel" ;;
    *.ko.xz) xz -dc "$file" > "$work/out/modules/kernel/${rel%.xz}" ;;
    *.ko.zst) zstd -dcq "$file" > "$work/out/modules/kernel/${rel%.zst}" ;;
  esac
  local deps
  deps="$(strings -a "$file" 2>/dev/null | sed -n 's/^depends=//p' | head -1)"
  [[ "$file" == *.ko ]] || deps="$(strings -a "$work/out/modules/kernel/${rel%.*}" | sed -n 's/^depends=//p' | head -1)"
  local d
  for d in ${deps//,/ }; do add_module "$d"; done
}
for m in "${modules[@]}"; do add_module "$m"; done
echo "$kver" > "$work/out/kernel-version"
echo "$pkg $(dpkg-deb -f "$deb" Version)" > "$work/out/package"
rm -rf "$dir"
mv "$work/out" "$dir"
touch "$dir/ready"
echo "$dir"
