#!/bin/sh
# boards/linux-gadget/gadget.sh — the USB gadget of the lumo thin client,
# through configfs and libcomposite (docs/porting.md §9). POSIX sh; needs
# the modules libcomposite and usb_f_fs (and a UDC driver), run as root.
#
#   gadget.sh setup [DIR]   the gadget $LUMO_GADGET (default "lumo"; VID:PID
#                           1209:0001, pid.codes' test pair: use your own in
#                           a product) with one configuration holding the
#                           FunctionFS function ffs.$LUMO_GADGET, mounted at
#                           DIR (default /dev/ffs-$LUMO_GADGET)
#   gadget.sh bind [UDC]    bind it to UDC (default: the first in
#                           /sys/class/udc), once the client has written its
#                           descriptors (DIR/ep1 exists): the host sees the
#                           device
#   gadget.sh unbind        the host sees it go (an unplug)
#   gadget.sh wait [DIR]    wait (10 s at most) for the client's descriptors
#
# Start the client (lumo-gadget, LUMO_FFS=DIR) between setup and bind.
# Several gadgets (one per UDC) differ by LUMO_GADGET.
set -eu
name=${LUMO_GADGET:-lumo}
G=/sys/kernel/config/usb_gadget/$name
F=ffs.$name
cmd=${1:-}
dir=${2:-/dev/ffs-$name}

setup() {
    [ -d /sys/kernel/config/usb_gadget ] || mount -t configfs none /sys/kernel/config
    mkdir -p "$G"
    echo 0x1209 >"$G/idVendor"
    echo 0x0001 >"$G/idProduct"
    echo 0x0200 >"$G/bcdUSB"
    mkdir -p "$G/strings/0x409" "$G/configs/c.1/strings/0x409" "$G/functions/$F"
    echo lumo >"$G/strings/0x409/manufacturer"
    echo "lumo thin client" >"$G/strings/0x409/product"
    echo "$name" >"$G/strings/0x409/serialnumber"
    echo "lumo stream" >"$G/configs/c.1/strings/0x409/configuration"
    echo 100 >"$G/configs/c.1/MaxPower"
    [ -e "$G/configs/c.1/$F" ] || ln -s "$G/functions/$F" "$G/configs/c.1/"
    mkdir -p "$dir"
    grep -q " $dir functionfs " /proc/mounts || mount -t functionfs "$name" "$dir"
}

case $cmd in
setup) setup ;;
bind)
    udc=${2:-$(ls /sys/class/udc | head -n 1)}
    echo "$udc" >"$G/UDC"
    ;;
unbind) echo "" >"$G/UDC" 2>/dev/null || true ;;
wait)
    i=0
    while [ ! -e "$dir/ep1" ] && [ $i -lt 100 ]; do sleep 0.1; i=$((i + 1)); done
    [ -e "$dir/ep1" ]
    ;;
*) echo "usage: gadget.sh setup|bind|unbind|wait [DIR|UDC]" >&2; exit 2 ;;
esac
