#!/bin/sh
# boards/lm3s6965evb/scene.sh DIR SEGMENTS — the 64 KiB client's scene:
# lumo-bake's default Cornell box (docs/scene-format.md) with a sphere of
# SEGMENTS segments in the dragon's place, written as ONE mesh with vertex
# colours (DIR/room.ply) and a scene file (DIR/scene.txt) beside it.
#
# One mesh because every progressive mesh costs its decoder on the client
# (about 30 KB at lumo-bake's 250-vertex batches, sdk/src/pmesh.c layout),
# whatever its size: six meshes would need 180 KB, one fits the 64 KiB
# board (docs/porting.md §8). Every triangle is wound so its normal looks
# into the room (walls) or out of the sphere.
dir=$1; seg=$2
mkdir -p "$dir"
awk -v seg="$seg" '
function vert(x, y, z, r, g, b) { vx[nv] = x; vy[nv] = y; vz[nv] = z; vc[nv] = r " " g " " b; return nv++ }
# a triangle whose normal must point along (dx, dy, dz)
function tri(a, b, c, dx, dy, dz,   ux, uy, uz, wx, wy, wz, nx, ny, nz) {
    ux = vx[b] - vx[a]; uy = vy[b] - vy[a]; uz = vz[b] - vz[a]
    wx = vx[c] - vx[a]; wy = vy[c] - vy[a]; wz = vz[c] - vz[a]
    nx = uy * wz - uz * wy; ny = uz * wx - ux * wz; nz = ux * wy - uy * wx
    f[nf++] = (nx * dx + ny * dy + nz * dz >= 0) ? a " " b " " c : a " " c " " b
}
# a rectangle o, o+u, o+u+v, o+v facing the room centre (0, 1, 0)
function quad(ox, oy, oz, ux, uy, uz, wx, wy, wz, r, g, b,   a, cx, cy, cz) {
    a = vert(ox, oy, oz, r, g, b); vert(ox + ux, oy + uy, oz + uz, r, g, b)
    vert(ox + ux + wx, oy + uy + wy, oz + uz + wz, r, g, b); vert(ox + wx, oy + wy, oz + wz, r, g, b)
    cx = ox + (ux + wx) / 2; cy = oy + (uy + wy) / 2; cz = oz + (uz + wz) / 2
    tri(a, a + 1, a + 2, -cx, 1 - cy, -cz); tri(a, a + 2, a + 3, -cx, 1 - cy, -cz)
}
BEGIN {
    nv = 0; nf = 0   # numbers from the start: an unset awk variable indexes "" not 0
    pi = atan2(0, -1)
    quad(-1, 0, -1, 0, 0, 2, 2, 0, 0, 191, 191, 191)        # floor
    quad(-1, 2, -1, 2, 0, 0, 0, 0, 2, 191, 191, 191)        # ceiling
    quad(-1, 0, -1, 2, 0, 0, 0, 2, 0, 191, 191, 191)        # back
    quad(-1, 0, -1, 0, 2, 0, 0, 0, 2, 161, 17, 13)          # left, red
    quad(1, 0, -1, 0, 0, 2, 0, 2, 0, 36, 115, 23)           # right, green
    rings = int(seg / 2); r = 0.45; cy = 0.45               # the sphere, gold
    top = vert(0, cy + r, 0, 184, 158, 115)
    for (i = 1; i < rings; i++)
        for (j = 0; j < seg; j++) {
            t = pi * i / rings; p = 2 * pi * j / seg
            vert(r * sin(t) * cos(p), cy + r * cos(t), r * sin(t) * sin(p), 184, 158, 115)
        }
    bot = vert(0, cy - r, 0, 184, 158, 115)
    for (j = 0; j < seg; j++) {
        k = (j + 1) % seg; a = top + 1 + j; b = top + 1 + k
        tri(top, a, b, vx[a] + vx[b], vy[a] + vy[b] - 2 * cy + 2 * r, vz[a] + vz[b])
        for (i = 1; i + 1 < rings; i++) {
            a = top + 1 + (i - 1) * seg + j; b = top + 1 + (i - 1) * seg + k
            c = a + seg; d = b + seg
            tri(a, c, d, vx[a] + vx[d], vy[a] + vy[d] - 2 * cy, vz[a] + vz[d])
            tri(a, d, b, vx[a] + vx[d], vy[a] + vy[d] - 2 * cy, vz[a] + vz[d])
        }
        a = top + 1 + (rings - 2) * seg + j; b = top + 1 + (rings - 2) * seg + k
        tri(bot, b, a, vx[a] + vx[b], vy[a] + vy[b] - 2 * cy - 2 * r, vz[a] + vz[b])
    }
    print "ply"; print "format ascii 1.0"; print "element vertex " nv
    print "property float x"; print "property float y"; print "property float z"
    print "property uchar red"; print "property uchar green"; print "property uchar blue"
    print "element face " nf; print "property list uchar int vertex_indices"; print "end_header"
    for (i = 0; i < nv; i++) printf "%.6f %.6f %.6f %s\n", vx[i], vy[i], vz[i], vc[i]
    for (i = 0; i < nf; i++) print "3 " f[i]
}' >"$dir/room.ply"
cat >"$dir/scene.txt" <<TXT
# the lm3s6965evb client's scene (boards/lm3s6965evb/scene.sh): the default
# Cornell box and a sphere of $seg segments as one mesh
mesh room.ply
light spot:0,1.95,0:0,-1,0:60:40,40,40
camera 0,1,3.4:0,1,0:0,1,0:40
TXT
