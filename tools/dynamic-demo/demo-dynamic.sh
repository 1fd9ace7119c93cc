#!/bin/sh
# tools/dynamic-demo/demo-dynamic.sh BIN DIR SCENE — make demo-dynamic
# (docs/dynamic.md). SCENE is baked into DIR/scene.lumo; lumo-server
# --dynamic serves it with the photon-streaming engine running on SCENE's
# motion (a spot light crossing the box, a sphere rolling through it) and
# a FIFO for live commands; lumo-client streams the scene, then pulls the
# lighting updates for 12 s drawing a frame every 1.5 s (DIR/frames/), and
# DIR/strip.png puts the eight frames side by side. Half way, a live
# command moves the sphere back to its place. The server's summary line
# says the latency from each change to settled lighting; dyn-error then
# measures the IVG from the VSLs against a path-traced bake of the same
# moments. Every process is under `timeout` and killed by the trap.
set -eu
bin=$1; dir=$2; scene=$3
. "$(dirname "$0")/../../tests/lib/background.sh"
rm -rf "$dir"; mkdir -p "$dir/frames"
"$bin/lumo-bake" "$scene" -o "$dir/scene.lumo" --grid 12 --spp 128 --no-progress 2>"$dir/bake.log" ||
    { cat "$dir/bake.log"; exit 1; }
fifo="$dir/commands"; mkfifo "$fifo"
spawn lumo-server "$dir/server.port" "$dir/server.log" timeout 120 "$bin/lumo-server" "$dir/scene.lumo" \
    --listen 127.0.0.1:0 --port-file "$dir/server.port" \
    --dynamic "$scene,vsl=400,pool=200000,batch=20000,commands=$fifo" || exit 1
server=$pid
port=$(cut -d' ' -f1 "$dir/server.port")
( sleep 7; echo "move object 5 -0.2,0,0.3" >"$fifo" ) &
pids="$pids $!"
timeout 60 "$bin/lumo-client" --connect "127.0.0.1:$port" --out "$dir/frames" --size 320x240 \
    --updates 12 --update-every 1500 --quiet >"$dir/client.log" 2>&1 || { cat "$dir/client.log"; exit 1; }
kill -TERM "$server"
i=0   # the engine stops after the serving loop has drained: its summary comes last
while ! grep -q "settled lighting" "$dir/server.log" && [ $i -lt 100 ]; do sleep 0.1; i=$((i + 1)); done
cat "$dir/client.log"
grep "dynamic" "$dir/server.log"
set -- "$dir"/frames/frame-update-00[0-7].png
labels=$(i=0; for f in "$@"; do printf '%st=%.1fs' "${sep:-}" "$(echo "$i * 1.5" | bc)"; sep=,; i=$((i + 1)); done)
"$bin/lumo-compare" "$@" -o "$dir/strip.png" --labels "$labels" >"$dir/compare.log" 2>&1 || { cat "$dir/compare.log"; exit 1; }
echo "demo-dynamic: $# frames in $dir/frames, side by side in $dir/strip.png"
"$bin/dyn-error" "$scene" --times 0,3,6,9 --vsl 400 --pool 200000 --batch 20000 --grid 12 --spp 1024
pids=""   # everything has ended: nothing for the trap to kill
exit 0
