#!/usr/bin/env bash
# Builds the live-camera guest's initramfs (uncompressed newc cpio) from installed files and the
# build's own: busybox-static, the vivid driver of the installed Debian kernel with the modules
# it needs (in the order modprobe would load them), v4l2-ctl and the tactile command with the
# shared libraries they need (and the dynamic loader), and the frames to feed.
#   make_live_initramfs.sh OUT.cpio TACTILE V4L2_CTL INIT MODULES_DIR BUSYBOX FRAMES
set -euo pipefail
out=$1 tactile=$2 v4l2ctl=$3 init=$4 moddir=$5 busybox=$6 frames=$7
source "$(dirname "$0")/initramfs.sh"
initramfs_root "$busybox" "$init"
# Without its debug information (a RelWithDebInfo build carries hundreds of MB of it), which the
# guest would hold in memory twice while the initramfs is unpacked.
strip --strip-debug -o "$root/bin/tactile" "$tactile"
cp "$v4l2ctl" "$root/bin/v4l2-ctl"
cp "$frames" "$root/frames.bgr"
# modprobe's own resolution of vivid's dependencies, one "insmod PATH" line each, in load order.
deps=$(modprobe --show-depends -S "$(basename "$moddir")" vivid)
if ! grep -q '/vivid\.ko' <<<"$deps"; then
  echo "make_live_initramfs: modprobe found no vivid module for $(basename "$moddir")" >&2
  exit 1
fi
: >"$root/lib/modules/order"
while read -r verb path _; do
  [[ $verb == insmod ]] || continue
  name=$(basename "$path")
  name=${name%.xz}
  name=${name%.zst}
  name=${name%.ko}
  initramfs_module "$path" "$name"
  echo "$name" >>"$root/lib/modules/order"
done <<<"$deps"
initramfs_libraries "$tactile" "$v4l2ctl"
initramfs_pack
