# The steps both guests' initramfs scripts share (sourced by make_initramfs.sh and
# make_live_initramfs.sh). Each script sets `out` (the cpio to write) before calling them.

# Makes the guest's root folder, $root, with busybox as /bin/busybox and INIT as /init. The root
# and a half-written OUT.tmp are removed when the script ends, however it ends.
initramfs_root() { # BUSYBOX INIT
  root=$(mktemp -d)
  trap 'rm -rf "$root" "${out:?}.tmp"' EXIT
  mkdir -p "$root"/{bin,dev,proc,sys,lib/modules,tmp}
  cp "$1" "$root/bin/busybox"
  cp "$2" "$root/init"
  chmod 755 "$root/init"
}

# Puts a kernel module (.ko, .ko.xz or .ko.zst, as Debian ships it) uncompressed into the root as
# /lib/modules/NAME.ko, for the init script's insmod.
initramfs_module() { # PATH NAME
  case "$1" in
    *.xz) xz -dc "$1" >"$root/lib/modules/$2.ko" ;;
    *.zst) zstd -qdc "$1" >"$root/lib/modules/$2.ko" ;;
    *) cp "$1" "$root/lib/modules/$2.ko" ;;
  esac
}

# Copies the shared libraries the programs need (and the dynamic loader) into the root at the
# paths the loader looks them up by.
initramfs_libraries() { # PROGRAM...
  local exe
  for exe in "$@"; do
    ldd "$exe" | awk '/=> \// {print $3} /^\t\/[^ ]+ \(/ {print $1}'
  done | sort -u | while read -r lib; do
    mkdir -p "$root$(dirname "$lib")"
    cp -L "$lib" "$root$lib"
  done
}

# Packs the root as an uncompressed newc cpio into $out, replacing it only once it is whole.
initramfs_pack() {
  (cd "$root" && find . -print0 | LC_ALL=C sort -z | cpio --null -o -H newc --quiet) >"$out.tmp"
  mv "$out.tmp" "$out"
}
