#!/bin/sh
# tests/usb/initramfs.sh OUT.cpio.gz KERNEL_ROOT GUEST_SCRIPT FILE... — the
# USB guest's initramfs (tests/usb/usb-test.sh): busybox (static), the
# kernel modules of a gadget looped back through dummy_hcd — udc-core,
# dummy_hcd, libcomposite, usb_f_fs and what they depend on (their
# .modinfo "depends=", in load order, into /modules and /modules/order) —
# /init (tests/usb/guest-init.sh), GUEST_SCRIPT as /test.sh, and each FILE
# into /bin (programs, with the shared libraries ldd names for them, at
# their own paths) or / (anything else, by its base name).
set -eu
out=$1; kroot=$2; script=$3; shift 3
here=$(dirname "$0")
root=$(mktemp -d "${TMPDIR:-/tmp}/lumo-initramfs.XXXXXX")
trap 'rm -rf "$root"' EXIT
mkdir -p "$root/bin" "$root/modules" "$root/proc" "$root/sys" "$root/dev" "$root/tmp" "$root/lib64"
cp /bin/busybox "$root/bin/busybox"
cp "$here/guest-init.sh" "$root/init"
cp "$script" "$root/test.sh"
chmod +x "$root/init" "$root/test.sh"

# Modules: depth first, each after what it depends on.
kmods=$(ls -d "$kroot"/lib/modules/*/kernel)
loaded=" "
ko_path() { find "$kmods" -name "$1.ko" -o -name "$1.ko.xz" | head -n 1; }
ko_deps() { objcopy -O binary --only-section=.modinfo "$1" /dev/stdout | tr '\0' '\n' | sed -n 's/^depends=//p' | tr ',' ' '; }
add_module() {
    case $loaded in *" $1 "*) return 0 ;; esac
    f=$(ko_path "$1")
    [ -n "$f" ] || { f=$(ko_path "$(echo "$1" | tr _ -)"); }
    [ -n "$f" ] || { echo "initramfs.sh: no module $1 in $kmods" >&2; exit 1; }
    for d in $(ko_deps "$f"); do add_module "$d"; done
    f=$(ko_path "$1")   # (sh has no locals: the calls above changed f)
    [ -n "$f" ] || f=$(ko_path "$(echo "$1" | tr _ -)")
    cp "$f" "$root/modules/"
    echo "$(basename "$f")" >>"$root/modules/order"
    loaded="$loaded$1 "
}
for m in configfs udc-core dummy_hcd libcomposite usb_f_fs; do add_module "$m"; done

for f in "$@"; do
    if [ -x "$f" ] && head -c 4 "$f" | grep -q ELF; then
        cp "$f" "$root/bin/"
        for lib in $(ldd "$f" | sed -n 's/.*=> \(\/[^ ]*\).*/\1/p; s/^[[:space:]]*\(\/[^ ]*\) (.*/\1/p'); do
            mkdir -p "$root$(dirname "$lib")"
            cp -L "$lib" "$root$lib"
        done
    else
        cp "$f" "$root/"
    fi
done
(cd "$root" && find . | busybox cpio -o -H newc 2>/dev/null) | gzip -1 >"$out"
