#!/usr/bin/env bash
# Builds the test guest's initramfs (uncompressed newc cpio) from installed files only:
# busybox-static, the USB host and HID modules of the installed Debian kernel, and the guest
# client with the shared libraries it needs (and the dynamic loader).
#   make_initramfs.sh OUT.cpio CLIENT INIT MODULES_DIR BUSYBOX
set -euo pipefail
out=$1 client=$2 init=$3 moddir=$4 busybox=$5
root=$(mktemp -d)
trap 'rm -rf "$root"' EXIT
mkdir -p "$root"/{bin,dev,proc,sys,lib/modules,tmp}
cp "$busybox" "$root/bin/busybox"
cp "$init" "$root/init"
chmod 755 "$root/init"
cp "$client" "$root/bin/vm_client"
for m in usb/common/usb-common usb/core/usbcore usb/host/xhci-hcd usb/host/xhci-pci \
         hid/hid hid/usbhid/usbhid hid/hid-generic; do
  src="$moddir/kernel/drivers/$m.ko"
  for ext in "" .xz .zst; do
    if [[ -f "$src$ext" ]]; then
      case "$ext" in
        .xz) xz -dc "$src$ext" >"$root/lib/modules/$(basename "$m").ko" ;;
        .zst) zstd -qdc "$src$ext" >"$root/lib/modules/$(basename "$m").ko" ;;
        *) cp "$src" "$root/lib/modules/" ;;
      esac
      continue 2
    fi
  done
  echo "make_initramfs: no module $m under $moddir" >&2
  exit 1
done
# Shared libraries at the paths the loader looks them up by.
ldd "$client" | awk '/=> \// {print $3} /^\t\/[^ ]+ \(/ {print $1}' | while read -r lib; do
  mkdir -p "$root$(dirname "$lib")"
  cp -L "$lib" "$root$lib"
done
(cd "$root" && find . -print0 | LC_ALL=C sort -z | cpio --null -o -H newc --quiet) >"$out.tmp"
mv "$out.tmp" "$out"
