#!/bin/busybox sh
# tests/usb/guest-init.sh — /init of the USB guest (tests/usb/initramfs.sh):
# busybox applets, /proc /sys /dev /tmp, loopback up, the modules in
# order, configfs; then /test.sh, whose lines go to the console
# (ttyS0), and power off. The host reads the verdict from the console log.
/bin/busybox --install -s /bin
export PATH=/bin
mount -t proc proc /proc
mount -t sysfs sysfs /sys
mount -t devtmpfs dev /dev
mount -t tmpfs tmp /tmp
ip link set lo up
for m in $(cat /modules/order); do
    args=""
    [ "$m" = dummy_hcd.ko ] && args="num=2"   # two UDCs: two devices at once
    insmod "/modules/$m" $args || echo "USBTEST bad: insmod $m"
done
mount -t configfs none /sys/kernel/config
echo "USBTEST info: booted in $(cut -d' ' -f1 /proc/uptime) s"
sh /test.sh
echo "USBTEST end"
poweroff -f
