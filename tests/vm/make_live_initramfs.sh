#!/usr/bin/env bash
# Builds the live-camera guest's initramfs (uncompressed newc cpio) from installed files and the
# build's own: busybox-static, the vivid driver of the installed Debian kernel with the modules
# it needs (in the order modprobe would load them), v4l2-ctl and the tactile command with the
# shared libraries they need (and the dynamic loader), and the frames to feed.
#   make_live_initramfs.sh OUT.cpio TACTILE V4L2_CTL INIT MODULES_DIR BUSYBOX FRAMES
set -euo pipefail
out=$1 tactile=$2 v4l2ctl=$3 init=$4 moddir=$5 busybox=$6 frames=$7
root=$(mktemp -d)
trap 'rm -rf "$root"' EXIT
mkdir -p "$root"/{bin,dev,proc,sys,lib/modules,tmp}
cp "$busybox" "$root/bin/busybox"
cp "$init" "$root/init"
chmod 755 "$root/init"
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
  case "$path" in
    *.xz) xz -dc "$path" >"$root/lib/modules/$name" ;;
    *.zst) zstd -qdc "$path" >"$root/lib/modules/$name" ;;
    *) cp "$path" "$root/lib/modules/$name" ;;
  esac
  echo "${name%.ko}" >>"$root/lib/modules/order"
done <<<"$deps"
# Shared libraries at the paths the loader looks them up by.
for exe in "$tactile" "$v4l2ctl"; do
  ldd "$exe" | awk '/=> \// {print $3} /^\t\/[^ ]+ \(/ {print $1}'
done | sort -u | while read -r lib; do
  mkdir -p "$root$(dirname "$lib")"
  cp -L "$lib" "$root$lib"
done
(cd "$root" && find . -print0 | LC_ALL=C sort -z | cpio --null -o -H newc --quiet) >"$out.tmp"
mv "$out.tmp" "$out"
