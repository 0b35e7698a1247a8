#!/usr/bin/env bash
# Screenshot of the viewer in a real X window (Xvfb, no GPU: lavapipe), e.g. for the README:
#   crates/viewer/scripts/screenshot.sh crates/viewer/docs/screenshot.png [viewer args...]
# Needs: xvfb xauth imagemagick mesa-vulkan-drivers libvulkan1; a release build of the viewer.
set -euo pipefail
out=${1:?usage: screenshot.sh OUT.png [viewer args...]}
shift
root=$(cd "$(dirname "$0")/../../.." && pwd)
bin="${CARGO_TARGET_DIR:-$root/target}/release/viewer"
[ -x "$bin" ] || (cd "$root" && cargo build --release -p viewer)
work=$(mktemp -d)
# Xvfb picks a free display and writes its number to fd 3.
Xvfb -displayfd 3 -screen 0 1280x800x24 -nolisten tcp 3>"$work/display" >/dev/null 2>&1 &
xvfb_pid=$!
trap 'kill "$xvfb_pid" 2>/dev/null || true; rm -rf "$work"' EXIT
for _ in $(seq 100); do [ -s "$work/display" ] && break; sleep 0.1; done
display=":$(head -n1 "$work/display")"
for _ in $(seq 100); do [ -S "/tmp/.X11-unix/X${display#:}" ] && break; sleep 0.1; done
mkdir -m 700 "$work/runtime"
DISPLAY=$display XDG_RUNTIME_DIR=$work/runtime WGPU_BACKEND=${WGPU_BACKEND:-vulkan} \
  "$bin" --ready-file "$work/ready" --exit-after-ready 2 "$@" &
viewer_pid=$!
for _ in $(seq 3000); do [ -e "$work/ready" ] && break; sleep 0.1; done
[ -e "$work/ready" ] || { echo "viewer never became ready" >&2; exit 1; }
sleep 0.5
import -display "$display" -window root "$out"
wait "$viewer_pid"
echo "wrote $out"
