#!/usr/bin/env bash
# Builds the test guest's initramfs (uncompressed newc cpio) from installed files only:
# busybox-static, the USB host and HID modules of the installed Debian kernel, and the guest
# client with the shared libraries it needs (and the dynamic loader).
#   make_initramfs.sh OUT.cpio CLIENT INIT MODULES_DIR BUSYBOX
set -euo pipefail
out=$1 client=$2 init=$3 moddir=$4 busybox=$5
source "$(dirname "$0")/initramfs.sh"
initramfs_root "$busybox" "$init"
cp "$client" "$root/bin/vm_client"
for m in usb/common/usb-common usb/core/usbcore usb/host/xhci-hcd usb/host/xhci-pci \
         hid/hid hid/usbhid/usbhid hid/hid-generic; do
  src="$moddir/kernel/drivers/$m.ko"
  for ext in "" .xz .zst; do
    if [[ -f "$src$ext" ]]; then
      initramfs_module "$src$ext" "$(basename "$m")"
      continue 2
    fi
  done
  echo "make_initramfs: no module $m under $moddir" >&2
  exit 1
done
initramfs_libraries "$client"
initramfs_pack
