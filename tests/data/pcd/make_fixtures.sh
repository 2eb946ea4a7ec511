#!/usr/bin/env bash
# Regenerates the scan fixtures in tests/data/{pcd,ply,bin} with third-party
# tools (Debian pcl-tools 1.13), so hba's readers are tested on files it did
# not write. Needs: apt-get install pcl-tools, python3, and ../shared/data/hku1.
# Usage: bash tests/data/pcd/make_fixtures.sh   (from the repository root)
set -euo pipefail

root=$(pwd)
scan=$root/../shared/data/hku1/Scans/000000.pcd
pcd=$root/tests/data/pcd
ply=$root/tests/data/ply
bin=$root/tests/data/bin
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

# 1. A real Livox scan cut to the 209 points with 11 <= x <= 12 (x y z intensity),
#    then the same cloud in all three PCD encodings (ascii with 9 digits: exact).
pcl_passthrough_filter "$scan" cut.pcd -field x -min 11 -max 12 -keep 0
pcl_convert_pcd_ascii_binary cut.pcd "$pcd/hku1_cut_ascii.pcd" 0 9
pcl_convert_pcd_ascii_binary cut.pcd "$pcd/hku1_cut_binary.pcd" 1
pcl_convert_pcd_ascii_binary cut.pcd "$pcd/hku1_cut_binary_compressed.pcd" 2

# 2. Extra fields before x y z: normals and curvature, in all three encodings.
pcl_normal_estimation "$pcd/hku1_cut_binary.pcd" normals.pcd -k 10
pcl_convert_pcd_ascii_binary normals.pcd "$pcd/normals_ascii.pcd" 0 9
pcl_convert_pcd_ascii_binary normals.pcd "$pcd/normals_binary.pcd" 1
pcl_convert_pcd_ascii_binary normals.pcd "$pcd/normals_binary_compressed.pcd" 2

# 3. A COUNT 33 field (FPFH histogram) first, on a smaller cut (11 <= x <= 11.2).
pcl_passthrough_filter "$scan" small.pcd -field x -min 11 -max 11.2 -keep 0
pcl_normal_estimation small.pcd small_normals.pcd -k 10
pcl_fpfh_estimation small_normals.pcd fpfh.pcd -radius 0.5
pcl_convert_pcd_ascii_binary fpfh.pcd "$pcd/fpfh_binary.pcd" 1
pcl_convert_pcd_ascii_binary fpfh.pcd "$pcd/fpfh_binary_compressed.pcd" 2

# 4. An organized 8 x 6 cloud (HEIGHT 6) with NaN holes and an unsigned rgb field,
#    from a depth image with a 2 x 2 hole of zeros (no return).
python3 - <<'PY'
import struct, zlib
def png(path, w, h, bitdepth, colortype, rows):
    def chunk(t, d):
        return struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t + d) & 0xffffffff)
    raw = b''.join(b'\x00' + r for r in rows)
    ihdr = struct.pack('>IIBBBBB', w, h, bitdepth, colortype, 0, 0, 0)
    open(path, 'wb').write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', ihdr) + chunk(b'IDAT', zlib.compress(raw)) + chunk(b'IEND', b''))
w, h = 8, 6
depth = [[0 if (2 <= u <= 3 and 1 <= v <= 2) else 1500 + 40 * u + 25 * v for u in range(w)] for v in range(h)]
png('depth.png', w, h, 16, 0, [b''.join(struct.pack('>H', d) for d in row) for row in depth])
png('color.png', w, h, 8, 2, [bytes(c for u in range(w) for c in (30 * u, 40 * v, 100)) for v in range(h)])
PY
pcl_png2pcd -format 1 --intensity_type FLOAT color.png depth.png organized.pcd
pcl_convert_pcd_ascii_binary organized.pcd "$pcd/organized_ascii.pcd" 0 9
pcl_convert_pcd_ascii_binary organized.pcd "$pcd/organized_binary.pcd" 1
pcl_convert_pcd_ascii_binary organized.pcd "$pcd/organized_binary_compressed.pcd" 2

# 5. float64 x y z intensity: PCL keeps a PLY's double properties as F 8 fields.
#    The PLY holds the first 14 points of the cut, as text.
{
  printf 'ply\nformat ascii 1.0\nelement vertex 14\n'
  printf 'property double x\nproperty double y\nproperty double z\nproperty double intensity\nend_header\n'
  grep -A14 '^DATA ascii' "$pcd/hku1_cut_ascii.pcd" | tail -n 14
} > double.ply
pcl_ply2pcd -format 1 double.ply float64.pcd
pcl_convert_pcd_ascii_binary float64.pcd "$pcd/float64_ascii.pcd" 0 17
pcl_convert_pcd_ascii_binary float64.pcd "$pcd/float64_binary.pcd" 1
pcl_convert_pcd_ascii_binary float64.pcd "$pcd/float64_binary_compressed.pcd" 2

# 6. PLY written by PCL (with its trailing "face 0" and "camera" elements).
pcl_pcd2ply -format 0 "$pcd/hku1_cut_binary.pcd" "$ply/hku1_cut_ascii.ply"
pcl_pcd2ply -format 1 "$pcd/hku1_cut_binary.pcd" "$ply/hku1_cut_binary.ply"

# 7. Triangle meshes: faces (list properties) after the vertices, written by
#    VTK (ascii, via pcl_vtk2ply) and by PCL (binary, via pcl_converter).
pcl_gp3_surface normals.pcd mesh.vtk -radius 1.0 -mu 3
pcl_vtk2ply mesh.vtk "$ply/mesh_ascii.ply"
pcl_converter "$ply/mesh_ascii.ply" "$ply/mesh_binary.ply" -f binary

# 8. KITTI .bin of the cut: float32 x y z intensity records (no tool writes
#    these, so python packs the ascii PCD's exact 9-digit values).
python3 - "$pcd/hku1_cut_ascii.pcd" "$bin/hku1_cut.bin" <<'PY'
import struct, sys
lines = open(sys.argv[1]).read().split('DATA ascii\n', 1)[1].split('\n')
values = [float(v) for line in lines if line.strip() for v in line.split()]
open(sys.argv[2], 'wb').write(struct.pack('<%df' % len(values), *values))
PY
