# Sourced by the multi-process tests and benchmarks: re-runs the calling script inside a private network
# namespace whose only interface is lo, with multicast routed on lo, so LCM's UDP multicast never reaches
# the host's network. Then sets `url` (LCM on lo), `tmp` (removed at exit) and `pids` (killed at exit).
if [ -z "${IMUCAL_IN_NETNS:-}" ]; then
  exec unshare -n env IMUCAL_IN_NETNS=1 bash "$0" "$@"
fi
ip link set lo up
ip route add 224.0.0.0/4 dev lo
# A 4 MiB receive buffer (the kernel default holds ~0.3 s at 1 kHz) rides out a busy machine.
url="udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304"
tmp="$(mktemp -d)"
pids=()
imucal_netns_cleanup() { for p in "${pids[@]}"; do kill -9 "$p" 2>/dev/null || true; done; rm -rf "$tmp"; }
trap imucal_netns_cleanup EXIT
