#!/usr/bin/env bash
# The vesselmesh command as a user runs it: exit codes, messages, outputs,
# and Gmsh (its Python API, when installed) reading what we write.
# Usage: cli_test.sh PATH/TO/vesselmesh
set -uo pipefail
VM=$1
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
failures=0
passes=0
check() {  # check NAME CONDITION...
  local name=$1; shift
  if "$@"; then passes=$((passes + 1)); else echo "FAIL: $name"; failures=$((failures + 1)); fi
}
expect_exit() {  # expect_exit CODE MESSAGE-SUBSTRING CMD...
  local code=$1 msg=$2; shift 2
  local out; out=$("$@" 2>&1); local rc=$?
  [[ $rc -eq $code ]] || { echo "  exit $rc, expected $code: $*"; echo "  $out"; return 1; }
  [[ -z $msg || $out == *"$msg"* ]] || { echo "  output lacks '$msg': $out"; return 1; }
}
json() {  # json FILE EXPR -> prints python expression over d
  python3 -c "import json,sys; d=json.load(open('$1')); print($2)"
}

check "help" expect_exit 0 "usage:" "$VM" --help
check "no arguments" expect_exit 2 "usage:" "$VM"
check "unknown command" expect_exit 2 "unknown command 'frobnicate'" "$VM" frobnicate
check "unknown option" expect_exit 2 "unknown option '--bogus'" "$VM" info x.stl --bogus
check "option twice" expect_exit 2 "option '--size' is given more than once" "$VM" mesh x.stl -o x.msh --size 1 --size 2
check "flag with a value" expect_exit 2 "option '--verify' takes no value" "$VM" mesh x.stl -o x.msh --verify=1
check "option without value" expect_exit 2 "option '--size' needs a value" "$VM" mesh x.stl -o x.msh --size
check "mesh option on info" expect_exit 2 "unknown option '--layers'" "$VM" info x.stl --layers 1
check "missing file" expect_exit 1 "cannot open '$T/none.stl'" "$VM" info "$T/none.stl"
: > "$T/empty.stl"
check "empty file" expect_exit 1 "empty file" "$VM" info "$T/empty.stl"
printf 'this is not a mesh at all\n' > "$T/garbage.stl"
check "garbage" expect_exit 1 "not a surface file this tool reads" "$VM" info "$T/garbage.stl"

check "phantom" expect_exit 0 "wrote" "$VM" phantom "$T/bif.stl" --kind bifurcation --voxel 0.1 --noise 0.3
check "phantom scale past float" expect_exit 2 "--scale needs a positive scale factor up to 1e30" "$VM" phantom "$T/x.stl" --scale 1e39
check "phantom bad kind" expect_exit 2 "--kind needs bifurcation, tube, aneurysm, torus, tree, crossing, outlets or root" "$VM" phantom "$T/x.stl" --kind blob
check "phantom tree" expect_exit 0 "wrote" "$VM" phantom "$T/tree.stl" --kind tree --voxel 0.12
check "tree has 11 openings" expect_exit 0 "openings:    11" "$VM" info "$T/tree.stl"
head -c 1000 "$T/bif.stl" > "$T/truncated.stl"
check "truncated" expect_exit 1 "truncated binary STL" "$VM" info "$T/truncated.stl"

# Where the input comes from: standard input, a pipe, a directory, a device.
check "stdin ('-')" expect_exit 0 "openings:    3" sh -c '"$1" info - < "$2"' _ "$VM" "$T/bif.stl"
check "pipe" expect_exit 0 "openings:    3" sh -c 'cat "$2" | "$1" info -' _ "$VM" "$T/bif.stl"
check "mesh from a pipe" expect_exit 0 "wrote" sh -c 'cat "$2" | "$1" mesh - -o "$3" --size 0.3 --layers 0' _ "$VM" "$T/bif.stl" "$T/pipe.msh"
check "directory" expect_exit 1 "is a directory: give a surface file" "$VM" info "$T"
check "device" expect_exit 1 "is a device, not a surface file" "$VM" info /dev/zero
# A binary STL announcing more triangles than the limit is refused from its
# header, before its 1.25 GB are read (a sparse file: nothing is written).
python3 -c "
import struct, sys
with open(sys.argv[1], 'wb') as f:
    f.write(b'big'.ljust(80, b' ') + struct.pack('<I', 25000001))
    f.truncate(84 + 50 * 25000001)
" "$T/huge.stl"
check "too many triangles, refused from the header" expect_exit 1 "the binary STL header announces 25000001 triangles" "$VM" info "$T/huge.stl"
# A gzip of 1 GiB of zeros (4.5 MB) is refused from its first inflated bytes,
# within a 256 MiB address space: the rest is never inflated.
head -c 1G /dev/zero | gzip -1 > "$T/zeros.stl.gz"
check "gzip of zeros, refused from its start" expect_exit 1 "gzip-compressed file: its first 65536 decompressed bytes are not the start of a surface file this tool reads" sh -c 'ulimit -v 262144 && "$1" mesh "$2" -o "$3"' _ "$VM" "$T/zeros.stl.gz" "$T/zeros.msh"
check "gzip of zeros: the message names them" expect_exit 1 "they are all zero bytes; the rest was not decompressed. Open the surface file itself" "$VM" mesh "$T/zeros.stl.gz" -o "$T/zeros.msh"
rm -f "$T/huge.stl"
# Text as segmentation tools write it: a UTF-8 byte order mark, a form feed
# or NUL in the solid's name, classic Mac line ends (CR only), UTF-16.
facet='facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n'
printf "\xef\xbb\xbfsolid t\n${facet}endsolid t\n" > "$T/bom.stl"
printf "solid a\fb\000c\n${facet}endsolid\n" > "$T/name.stl"
printf "solid t\n${facet}endsolid t\n" | tr '\n' '\r' > "$T/cr.stl"
printf "solid t\n${facet}endsolid t\n" | iconv -f ASCII -t UTF-16 > "$T/utf16.stl"
for f in bom name cr utf16; do
  check "ASCII STL: $f" expect_exit 0 "(ASCII STL, 1 triangles)" "$VM" info "$T/$f.stl"
done
check "UTF-16 said" expect_exit 0 "UTF-16 text" "$VM" info "$T/utf16.stl"

"$VM" info "$T/bif.stl" --json > "$T/info.json"
check "info json openings" [ "$(json "$T/info.json" "len(d['openings'])")" = 3 ]
check "info json genus" [ "$(json "$T/info.json" "d['genus']")" = 0 ]
check "info json components" [ "$(json "$T/info.json" "d['components']")" = 1 ]
check "info json quality" [ "$(json "$T/info.json" "0 <= d['quality']['min'] <= d['quality']['mean'] <= 1")" = True ]
check "info text" expect_exit 0 "openings:    3" "$VM" info "$T/bif.stl"
"$VM" phantom "$T/dirty.stl" --kind aneurysm --dirty > /dev/null && "$VM" info "$T/dirty.stl" --json > "$T/dirty.json"
check "dirty phantom: info lists closed holes apart from the 3 openings, mesh succeeds" [ "$(json "$T/dirty.json" "len(d['openings']) == 3 and len(d['holes']) >= 5 and all(h['closed'] for h in d['holes'])")" = True ] && check "mesh dirty" expect_exit 0 "wrote" "$VM" mesh "$T/dirty.stl" -o "$T/dirty.msh"
# A SimVascular-like capped model with 186 labelled faces and 20 caps of 6
# triangles (phantom --kind outlets as a labelled .vtp): at default options
# every cap becomes an opening and the volume is written with a wall, an
# inlet and 21 outlets.
check "outlets phantom as labelled VTP" expect_exit 0 "wrote" "$VM" phantom "$T/outlets.vtp" --kind outlets
check "outlets phantom: VTP with ModelFaceID" grep -q 'Name="ModelFaceID"' "$T/outlets.vtp"
check "outlets phantom meshes at defaults" expect_exit 0 "outlet_21" "$VM" mesh "$T/outlets.vtp" -o "$T/outlets.msh" --report "$T/outlets.json" --verify
check "outlets phantom: 22 caps removed, groups wall, inlet, outlet_1..21, lumen" [ "$(json "$T/outlets.json" "d['input']['caps_removed'] == 22 and d['input']['label_array'] == 'ModelFaceID' and [g['name'] for g in d['output']['groups']] == ['wall', 'inlet'] + ['outlet_%d' % k for k in range(1, 22)] + ['lumen'] and all(g['elements'] > 0 for g in d['output']['groups'])")" = True ]
check "outlets phantom: the report lists the fallback patches (none here)" [ "$(json "$T/outlets.json" "d['output']['remesh']['fallback_patches'] == [] and d['output']['remesh']['splits'] >= 0")" = True ]
"$VM" info "$T/dirty.stl" --repair off > "$T/dirty-off.txt" 2>&1
check "dirty phantom, repair off: the fin's 2-vertex loop is a slit with its place, not an opening of radius 0" grep -q "^slits:       1 .* e.g. at (" "$T/dirty-off.txt"
check "dirty phantom, repair off: no opening of 2 vertices" bash -c "! grep -q ', 2 vertices' '$T/dirty-off.txt'"

# A tube (radius 1 along z) whose wall near (1, 0, 4) is pushed through the
# opposite wall: re-surfaced by default, saying where; with --repair off,
# info says where it crosses itself and mesh fails saying so.
python3 - "$T/dent.stl" <<'PY'
import math, sys
n, m, p = 48, 40, []
for j in range(m + 1):
    for i in range(n):
        a, z = 2 * math.pi * i / n, 8.0 * j / m
        d2 = 2 * (1 - math.cos(a)) + (z - 4) ** 2
        p.append((math.cos(a) - 2.6 * math.exp(-d2 / (2 * 0.35 ** 2)), math.sin(a), z))
with open(sys.argv[1], 'w') as f:
    f.write('solid dent\n')
    for j in range(m):
        for i in range(n):
            a, b = j * n + i, j * n + (i + 1) % n
            for t in ((a, b, b + n), (a, b + n, a + n)):
                f.write('facet normal 0 0 0\nouter loop\n' + ''.join('vertex %.9g %.9g %.9g\n' % p[v] for v in t) + 'endloop\nendfacet\n')
    f.write('endsolid dent\n')
PY
check "self-crossing: re-surfaced by default, saying where" expect_exit 0 "warning: the surface crossed itself at (-" "$VM" info "$T/dent.stl"
check "self-crossing: none left after the repair" expect_exit 0 "self-crossings: none" "$VM" info "$T/dent.stl"
check "self-crossing: json lists the place re-surfaced near (-1, 0, 4)" [ "$("$VM" info "$T/dent.stl" --json | python3 -c "import json,sys; c=json.load(sys.stdin)['repairs']['crossings_resurfaced']; print(len(c) == 1 and c[0]['resolved'] and abs(c[0]['where'][0] + 1) < 0.2 and abs(c[0]['where'][2] - 4) < 0.7)")" = True ]
check "self-crossing: meshes by default" expect_exit 0 "wall" "$VM" mesh "$T/dent.stl" -o "$T/dent.msh"
check "self-crossing, repair off: info names the place" expect_exit 0 "self-crossings: 1 place (" "$VM" info "$T/dent.stl" --repair off
check "self-crossing, repair off: a warning says where" expect_exit 0 "warning: the surface crosses itself at 1 place" "$VM" info "$T/dent.stl" --repair off
check "self-crossing, repair off: json place near (-1, 0, 4)" [ "$("$VM" info "$T/dent.stl" --json --repair off | python3 -c "import json,sys; c=json.load(sys.stdin)['self_crossings']; print(c['pairs'] > 0 and c['place_count'] == 1 and abs(c['places'][0][0] + 1) < 0.1 and abs(c['places'][0][2] - 4) < 0.6)")" = True ]
check "self-crossing, repair off: mesh fails naming it" expect_exit 1 "error: $T/dent.stl: the input crosses itself at (-" "$VM" mesh "$T/dent.stl" -o "$T/dent.msh" --repair off
dent_unit=$("$VM" info "$T/dent.stl" --json | python3 -c "import json,sys; print(json.load(sys.stdin)['units']['unit'])")
check "self-crossing, repair off: the refusal says what to do, in CLI words" expect_exit 1 ") $dent_unit (1 place; fix it in the segmentation, or cut that part off with --clip-plane): " "$VM" mesh "$T/dent.stl" -o "$T/dent.msh" --repair off

# Two vessels that pass into each other, each its own shell: re-surfaced
# into one and meshed with an inlet and 3 outlets; with --repair off refused.
"$VM" phantom "$T/crossing.stl" --kind crossing --voxel 0.15 > /dev/null
check "crossing vessels: mesh with defaults" expect_exit 0 "wrote" "$VM" mesh "$T/crossing.stl" -o "$T/crossing.msh" --report "$T/crossing.json"
check "crossing vessels: wall, inlet, 3 outlets" [ "$(json "$T/crossing.json" "sorted(g['name'] for g in d['output']['groups'] if g['dim'] == 2)")" = "['inlet', 'outlet_1', 'outlet_2', 'outlet_3', 'wall']" ]
check "crossing vessels, repair off: refused, saying where" expect_exit 1 "crosses itself at (" "$VM" mesh "$T/crossing.stl" -o "$T/crossing-off.msh" --repair off
# Damaged ends (folds, a flap through the wall, tiny loops, a twist): each
# trimmed back to a clean cross-section, and meshed.
"$VM" phantom "$T/damaged.stl" --damaged-ends --voxel 0.12 > /dev/null
check "damaged ends: info says each end was trimmed, where" [ "$("$VM" info "$T/damaged.stl" 2>&1 | grep -c "^warning: the vessel end at (.*) is damaged (.*): trimmed back to its first clean cross-section")" = 3 ]
check "damaged ends: 3 openings, all from the trim's cuts" [ "$("$VM" info "$T/damaged.stl" --json | python3 -c "import json,sys; d=json.load(sys.stdin); print(len(d['openings']) == 3 and all(o['source'] == 'clip' for o in d['openings']) and len(d['repairs']['damaged_ends']) == 3)")" = True ]
check "damaged ends: mesh with defaults" expect_exit 0 "outlet_2" "$VM" mesh "$T/damaged.stl" -o "$T/damaged.msh"
check "damaged ends, repair off: refused as not orientable" expect_exit 1 "not orientable" "$VM" mesh "$T/damaged.stl" -o "$T/damaged-off.msh" --repair off
check "self-crossing: none on a clean phantom" expect_exit 0 "self-crossings: none" "$VM" info "$T/bif.stl"

# Full precision from ASCII STL: a small tube (radius 0.01) 1e5 from the
# origin, written with 17 digits. Float32 corners (spacing 2^-7 there) would
# collapse it; it meshes as the same tube at the origin does.
"$VM" phantom "$T/small.stl" --kind tube --scale 0.01 > /dev/null
python3 - "$T/small.stl" "$T/far.stl" <<'PY'
import struct, sys
b = open(sys.argv[1], "rb").read()
out = ["solid far\n"]
for t in range(struct.unpack_from("<I", b, 80)[0]):
    f = struct.unpack_from("<12f", b, 84 + 50 * t)
    out.append("facet normal 0 0 0\nouter loop\n")
    for k in range(3):
        out.append("vertex %.17g %.17g %.17g\n" % tuple(x + 1e5 for x in f[3 + 3 * k:6 + 3 * k]))
    out.append("endloop\nendfacet\n")
open(sys.argv[2], "w").write("".join(out) + "endsolid far\n")
PY
check "ASCII 1e5 from the origin: meshed" expect_exit 0 "wrote" "$VM" mesh "$T/far.stl" -o "$T/far.msh" --report "$T/far.json"
"$VM" mesh "$T/small.stl" -o "$T/small.msh" --report "$T/small.json" > /dev/null 2>&1
check "ASCII 1e5 from the origin: every vertex kept, the lumen's volume" [ "$(python3 -c "
import json
f, s = (json.load(open('$T/' + n + '.json')) for n in ('far', 'small'))
print(f['input']['format'], f['input']['vertices'] == s['input']['vertices'], f['input']['bounding_box']['min'][0] > 99999,
      abs(f['output']['volume']['lumen_volume'] / s['output']['volume']['lumen_volume'] - 1) < 0.01)")" = "ASCII STL True True True" ]

# An oversampled tube (voxel 0.03: about 218,000 triangles): decimated
# before remeshing, unless --decimate off; the report says so.
"$VM" phantom "$T/fine.stl" --kind tube --voxel 0.03 > /dev/null
check "oversampled: decimated first" expect_exit 0 "decimated: " "$VM" mesh "$T/fine.stl" -o "$T/fine.msh" --surface-only --size 0.3 --report "$T/fine.json"
check "oversampled: the report's count is under an eighth of the input's" [ "$(json "$T/fine.json" "0 < d['output']['remesh']['decimated_triangles'] < d['input']['triangles'] / 8")" = True ]
check "oversampled, --decimate off: remeshed as it is" bash -c 'out=$("$1" mesh "$2" -o "$3" --surface-only --size 0.3 --decimate off) && [[ $out == *"wrote"* && $out != *"decimated:"* ]]' _ "$VM" "$T/fine.stl" "$T/fine-off.msh"
check "--decimate takes auto or off" expect_exit 2 "--decimate needs auto or off" "$VM" mesh "$T/fine.stl" -o "$T/x.msh" --decimate yes
# Threads: the same file with 1 and 2 (the 218,000 triangles span several
# chunks of the parallel loops); the count is not written into it.
check "--threads 1 meshes" expect_exit 0 "wrote" "$VM" mesh "$T/fine.stl" -o "$T/fine-t1.msh" --surface-only --size 0.3 --threads 1
check "--threads 2 meshes" expect_exit 0 "wrote" "$VM" mesh "$T/fine.stl" -o "$T/fine-t2.msh" --surface-only --size 0.3 --threads 2
check "--threads 1 and 2 write the same bytes" cmp -s "$T/fine-t1.msh" "$T/fine-t2.msh"
check "info takes --threads" expect_exit 0 "welded:" "$VM" info "$T/fine.stl" --threads 2
check "--threads needs a count" expect_exit 2 "--threads needs an integer from 0 (all cores) to 256" "$VM" info "$T/fine.stl" --threads -1
check "mesh needs -o" expect_exit 2 "-o OUT.msh" "$VM" mesh "$T/bif.stl"
check "mesh bad version" expect_exit 2 "--msh-version needs 4.1 or 2.2" "$VM" mesh "$T/bif.stl" -o "$T/x.msh" --msh-version 3
check "mesh 4.1" expect_exit 0 "wrote" "$VM" mesh "$T/bif.stl" -o "$T/bif41.msh" --report "$T/report.json" --verify
check "mesh 2.2" expect_exit 0 "wrote" "$VM" mesh "$T/bif.stl" -o "$T/bif22.msh" --msh-version 2.2
check "msh 4.1 header" [ "$(sed -n 2p "$T/bif41.msh")" = "4.1 0 8" ]
check "msh 2.2 header" [ "$(sed -n 2p "$T/bif22.msh")" = "2.2 0 8" ]
check "refine: a bad radius" expect_exit 2 "--refine needs 5 numbers X,Y,Z,R,H" "$VM" mesh "$T/bif.stl" -o "$T/x.msh" --refine 0,0,0,0,0.1
check "refine: a size too small for floating point" expect_exit 2 "below 1e-4 of the model's size" "$VM" mesh "$T/bif.stl" -o "$T/x.msh" --refine 1e-300,1e-300,1e-300,1e-300,1e-300
check "refine: finer within the sphere" expect_exit 0 "wrote" "$VM" mesh "$T/bif.stl" -o "$T/refined.msh" --surface-only --refine 0,0,0,1,0.08 --report "$T/refined.json"
check "refine: the smallest size is the sphere's" [ "$(json "$T/refined.json" "abs(d['output']['remesh']['size']['min'] - 0.08) < 1e-9")" = True ]
# The size field before meshing: info --size-field writes the prepared
# surface with point data radius (R) and size (h) in the model's unit.
vtp_arrays() {  # vtp_arrays FILE: prints a dict name -> list of Float64 point data values
  python3 - "$1" <<'PY'
import re, struct, sys
d = open(sys.argv[1], 'rb').read()
head, data = d.split(b'<AppendedData encoding="raw">', 1)
data = data[data.index(b'_') + 1:]
pd = re.search(rb'<PointData>(.*?)</PointData>', head, re.S).group(1)
out = {}
for m in re.finditer(rb'<DataArray type="Float64" Name="(\w+)" format="appended" offset="(\d+)"', pd):
    off = int(m.group(2)); n = struct.unpack('<Q', data[off:off + 8])[0]
    out[m.group(1).decode()] = struct.unpack('<%dd' % (n // 8), data[off + 8:off + 8 + n])
print(repr(out))
PY
}
check "size field: written" expect_exit 0 "size field:  wrote $T/sf.vtp: radius" "$VM" info "$T/bif.stl" --size-field "$T/sf.vtp" --per-circumference 16 --gradation 0
check "size field: h = 2 pi R / N, R near the phantom's (parent radius 1)" [ "$(vtp_arrays "$T/sf.vtp" | python3 -c "
import math, sys
a = eval(sys.stdin.read()); r, h = a['radius'], a['size']
med = sorted(r)[len(r) // 2]
print(len(r) == len(h) > 100 and 0.5 < med < 1.1 and all(abs(y - 2 * math.pi * x / 16) <= 1e-12 * x for x, y in zip(r, h)))")" = True ]
check "size field: a refinement sphere's size is the smallest" expect_exit 0 "size field:" "$VM" info "$T/bif.stl" --size-field "$T/sfr.vtp" --refine 0,0,0,1,0.08 --size-max 0.4
check "size field: min H, max size-max" [ "$(vtp_arrays "$T/sfr.vtp" | python3 -c "
import sys
h = eval(sys.stdin.read())['size']
print(abs(min(h) - 0.08) < 1e-12 and max(h) <= 0.4)")" = True ]
check "size field: a bad refinement refused as mesh refuses it" expect_exit 2 "below 1e-4 of the model's size" "$VM" info "$T/bif.stl" --size-field "$T/x.vtp" --refine 0,0,0,1,1e-9
check "size field: needs a file name" expect_exit 2 "option '--size-field' needs a value" "$VM" info "$T/bif.stl" --size-field
check "size field: JSON stays JSON" [ "$("$VM" info "$T/bif.stl" --json --size-field "$T/sfj.vtp" | python3 -c "import json,sys; print(len(json.load(sys.stdin)['openings']))")" = 3 ]
if [[ -x /usr/bin/python3 ]] && /usr/bin/python3 -c "import vtk" 2>/dev/null; then
  check "size field: VTK reads radius and size" [ "$(/usr/bin/python3 -c "
import vtk
r = vtk.vtkXMLPolyDataReader(); r.SetFileName('$T/sf.vtp'); r.Update()
p = r.GetOutput(); pd = p.GetPointData()
print(p.GetNumberOfPoints() > 100 and pd.GetArray('radius').GetNumberOfTuples() == p.GetNumberOfPoints() and pd.GetArray('size') is not None)")" = True ]
fi
check "mesh bad size" expect_exit 2 "--size needs a positive length" "$VM" mesh "$T/bif.stl" -o "$T/x.msh" --size -1
check "mesh bad N" expect_exit 2 "--per-circumference needs" "$VM" mesh "$T/bif.stl" -o "$T/x.msh" --per-circumference 2
check "mesh bad param" expect_exit 2 "lscm, harmonic or floater" "$VM" mesh "$T/bif.stl" -o "$T/x.msh" --param conformal
check "mesh bad mesher" expect_exit 2 "frontal, delaunay or adapt" "$VM" mesh "$T/bif.stl" -o "$T/x.msh" --mesher2d quad
check "mesh min > max" expect_exit 2 "--size-min must be >= 0 and at most --size-max" "$VM" mesh "$T/bif.stl" -o "$T/x.msh" --size-min 2 --size-max 1
check "mesh surface-only uniform" expect_exit 0 "remeshed:" "$VM" mesh "$T/bif.stl" -o "$T/u.msh" --surface-only --size 0.2 --param floater --mesher2d delaunay --report "$T/u.json"
check "mesh bad fidelity" expect_exit 2 "--fidelity needs a fraction of h in [0, 1]" "$VM" mesh "$T/bif.stl" -o "$T/x.msh" --fidelity 3
check "mesh fidelity 0" expect_exit 0 "remeshed:" "$VM" mesh "$T/bif.stl" -o "$T/f0.msh" --surface-only --size 0.2 --fidelity 0 --report "$T/f0.json"
check "fidelity 0 pins nothing" [ "$(json "$T/f0.json" "d['output']['remesh']['fidelity']['pinned_vertices']")" = 0 ]
check "mesh bad inlet" expect_exit 2 "--inlet must be between 1 and the number of openings (3)" "$VM" mesh "$T/bif.stl" -o "$T/x.msh" --inlet 7
check "mesh inlet not a number" expect_exit 2 "--inlet needs an opening number" "$VM" mesh "$T/bif.stl" -o "$T/x.msh" --inlet first
check "mesh no-remesh" expect_exit 0 "wrote" "$VM" mesh "$T/bif.stl" -o "$T/n.msh" --no-remesh --layers 0
check "mesh with vessel wall" expect_exit 0 "vessel wall: 4 layers" "$VM" mesh "$T/bif.stl" -o "$T/w.msh" --size 0.25 --wall-thickness 0.1 --tag-layer --report "$T/w.json"
check "vessel wall groups" [ "$(json "$T/w.json" "','.join(g['name'] for g in d['output']['groups'])")" = "wall,inlet,outlet_1,outlet_2,outer_wall,wall_inlet,wall_outlet_1,wall_outlet_2,lumen,boundary_layer,vessel_wall" ]
check "mesh with prisms" expect_exit 0 "wrote" "$VM" mesh "$T/bif.stl" -o "$T/p.msh" --size 0.25 --prisms --verify --report "$T/p.json"
if /usr/bin/python3 -c "import gmsh" 2>/dev/null; then
  got=$(/usr/bin/python3 - "$T/p.msh" <<'PY'
import sys, gmsh, numpy as np
gmsh.initialize()
gmsh.option.setNumber("General.Verbosity", 0)
gmsh.open(sys.argv[1])
tags, coords, _ = gmsh.model.mesh.getNodes()
xyz = np.zeros((int(tags.max()) + 1, 3))
xyz[tags.astype(int)] = coords.reshape(-1, 3)
types = set()
worst = 1.0
for dim in (2, 3):
    for ty, _, nodes in zip(*gmsh.model.mesh.getElements(dim)):
        types.add(int(ty))
        if ty == 6:  # corner Jacobians of every prism
            p = nodes.astype(int).reshape(-1, 6)
            for a, b, c, d in [(0, 1, 2, 3), (1, 2, 0, 4), (2, 0, 1, 5), (3, 5, 4, 0), (4, 3, 5, 1), (5, 4, 3, 2)]:
                A, B, C, D = (xyz[p[:, k]] for k in (a, b, c, d))
                worst = min(worst, np.einsum("ij,ij->i", np.cross(B - A, C - A), D - A).min())
print(sorted(types), "valid" if worst > 0 else "INVERTED")
gmsh.finalize()
PY
)
  check "gmsh reads prisms and quads, none inverted" [ "$(printf '%s\n' "$got" | tail -n 1)" = "[2, 3, 4, 6] valid" ]
fi
check "mesh bad layers" expect_exit 2 "--layers needs a number of layers" "$VM" mesh "$T/bif.stl" -o "$T/x.msh" --layers -2
check "mesh bad wall thickness" expect_exit 2 "--wall-thickness needs a fraction" "$VM" mesh "$T/bif.stl" -o "$T/x.msh" --wall-thickness 1.5
check "mesh unwritable output" expect_exit 1 "cannot write" "$VM" mesh "$T/bif.stl" -o "$T/no/such/dir/x.msh"

# Physical tags unique across dimensions (gmshToFoam names cell zones by number).
unique_tags() {  # unique_tags FILE.msh: no tag number in two dimensions
  python3 - "$1" <<'PY'
import sys
lines = open(sys.argv[1]).read().split("\n")
i = lines.index("$PhysicalNames")
groups = [l.split()[:2] for l in lines[i + 2:i + 2 + int(lines[i + 1])]]
tags = [t for d, t in groups]
print("unique" if len(set(tags)) == len(tags) and len(tags) > 1 else "SHARED " + str(groups))
PY
}
msh_types() {  # msh_types FILE.msh: the element types in it, sorted (MSH 4.1 or 2.2)
  python3 - "$1" <<'PY'
import sys
lines = open(sys.argv[1]).read().split("\n")
version = lines[1].split()[0]
i = lines.index("$Elements") + 1
types = set()
if version == "2.2":
    for l in lines[i + 1:i + 1 + int(lines[i])]:
        types.add(int(l.split()[1]))
else:
    blocks, i = int(lines[i].split()[0]), i + 1
    for _ in range(blocks):
        dim, ent, ty, n = map(int, lines[i].split())
        types.add(ty)
        i += n + 1
print(",".join(map(str, sorted(types))))
PY
}
check "msh 4.1 tags unique across dimensions" [ "$(unique_tags "$T/w.msh")" = unique ]
check "msh 2.2 tags unique across dimensions" [ "$(unique_tags "$T/bif22.msh")" = unique ]
check "report groups carry the tags" [ "$(json "$T/w.json" "[(g['dim'], g['tag']) for g in d['output']['groups']][-3:]")" = "[(3, 9), (3, 10), (3, 11)]" ]

# Solver presets: defaults under the user's options.
check "svfsi with a vessel wall" expect_exit 0 "wrote" "$VM" mesh "$T/bif.stl" -o "$T/fsi/" --solver svfsi --wall-thickness 0.1 --size 0.4 --layers 1
check "svfsi: fluid and solid mesh-complete folders sharing the wall" [ -f "$T/fsi/fluid/mesh-complete.mesh.vtu" -a -f "$T/fsi/solid/mesh-complete.mesh.vtu" -a -f "$T/fsi/fluid/mesh-surfaces/wall.vtp" -a -f "$T/fsi/solid/mesh-surfaces/wall.vtp" -a -f "$T/fsi/solid/mesh-surfaces/outer_wall.vtp" -a ! -e "$T/fsi/fluid/mesh-surfaces/outer_wall.vtp" ]
check "older name --for: the solver option" expect_exit 2 "--solver needs gmsh, openfoam, fenics or svfsi" "$VM" mesh "$T/bif.stl" -o "$T/x.msh" --for ansys
check "bad solver" expect_exit 2 "--solver needs gmsh, openfoam, fenics or svfsi" "$VM" mesh "$T/bif.stl" -o "$T/x.msh" --solver ansys
check "openfoam preset (the .msh name is yours)" expect_exit 0 "preset openfoam: prisms true, msh_version 2.2, output_units m (the preset); format msh (yours)" "$VM" mesh "$T/bif.stl" -o "$T/foam.msh" --size 0.25 --solver openfoam --report "$T/foam.json"
check "openfoam: MSH 2.2" [ "$(sed -n 2p "$T/foam.msh")" = "2.2 0 8" ]
check "openfoam: prisms (type 6) kept" [ "$(msh_types "$T/foam.msh")" = "2,3,4,6" ]
check "openfoam: the report lists the preset's settings" [ "$(json "$T/foam.json" "d['preset']['solver'], [s['from'] for s in d['preset']['settings']]")" = "openfoam ['preset', 'preset', 'preset', 'user']" ]
bif_unit=$(json "$T/info.json" "d['units']['unit'] + ' (' + d['units']['confidence']")
check "openfoam: a guessed unit converted warns" expect_exit 0 "written in m from a guessed unit, $bif_unit: " "$VM" mesh "$T/bif.stl" -o "$T/foam.msh" --size 0.25 --layers 2 --solver openfoam
# The phantom reaches about 6 units from the origin: in metres, 6 times the unit.
per_unit=$(json "$T/info.json" "{'mm': 0.001, 'cm': 0.01, 'm': 1}[d['units']['unit']]")
check "openfoam: coordinates in metres" [ "$(awk -v f="$per_unit" '/^\$Nodes/{n=1;getline;next} /^\$EndNodes/{n=0} n{for(i=2;i<=4;i++){x=$i<0?-$i:$i; if(x>m)m=x}} END{print (m>f && m<20*f)}' "$T/foam.msh")" = 1 ]
check "openfoam: explicit version wins" expect_exit 0 "msh_version 4.1, format msh (yours)" "$VM" mesh "$T/bif.stl" -o "$T/foam41.msh" --size 0.25 --layers 2 --solver openfoam --msh-version 4.1
check "openfoam: explicit version written" [ "$(sed -n 2p "$T/foam41.msh")" = "4.1 0 8" ]
check "fenics preset" expect_exit 0 "preset fenics: prisms false" "$VM" mesh "$T/bif.stl" -o "$T/fenics.msh" --size 0.25 --layers 2 --solver fenics
check "fenics: tetrahedra only" [ "$(msh_types "$T/fenics.msh")" = "2,4" ]
check "fenics + --prisms: prisms (yours)" expect_exit 0 "prisms true, format msh (yours)" "$VM" mesh "$T/bif.stl" -o "$T/fenicsp.msh" --size 0.25 --layers 2 --solver fenics --prisms
check "svfsi preset: a mesh-complete folder" expect_exit 0 "format mesh-complete (the preset)" "$VM" mesh "$T/bif.stl" -o "$T/svfsi-out" --size 0.25 --layers 2 --solver svfsi
check "svfsi folder written" [ -f "$T/svfsi-out/mesh-complete.mesh.vtu" ] && [ -f "$T/svfsi-out/mesh-surfaces/wall.vtp" ]
check "svfsi: a .msh name wins" expect_exit 0 "format msh (yours)" "$VM" mesh "$T/bif.stl" -o "$T/svfsi.msh" --size 0.25 --layers 2 --solver svfsi
check "no preset: a name without extension refused" expect_exit 2 "cannot tell the output format" "$VM" mesh "$T/bif.stl" -o "$T/noext" --size 0.25

# First layer from a target y+.
check "y+ sets the first layer" expect_exit 0 "first layer: " "$VM" mesh "$T/bif.stl" -o "$T/yplus.msh" --size 0.25 --layers 3 --first-layer-yplus 1 --inlet-velocity 0.3 --report "$T/yplus.json"
check "y+ in the report" [ "$(json "$T/yplus.json" "' '.join(str(x) for x in (lambda y: (y['yplus'], y['inlet'], y['density'], y['viscosity'], abs(y['height'] * $per_unit - y['height_m']) < 1e-12 * y['height_m'], 0 < y['height'] < 0.5))(d['first_layer_yplus']))")" = "1 inlet 1060 0.0035 True True" ]
check "y+ and --first-layer refused" expect_exit 2 "--first-layer-yplus and --first-layer both set the first layer's height" "$VM" mesh "$T/bif.stl" -o "$T/x.msh" --first-layer-yplus 1 --inlet-velocity 0.3 --first-layer 0.01
check "y+ needs a velocity" expect_exit 2 "--first-layer-yplus needs the flow's --inlet-velocity" "$VM" mesh "$T/bif.stl" -o "$T/x.msh" --first-layer-yplus 1
check "density alone refused" expect_exit 2 "--density sizes the first layer from a target y+" "$VM" mesh "$T/bif.stl" -o "$T/x.msh" --density 1000

# Two components: refused, then accepted with --largest-component-only.
cat "$T/bif.stl" > "$T/two.stl"
python3 - "$T/bif.stl" "$T/two.stl" <<'PY'
import struct, sys
data = open(sys.argv[1], 'rb').read()
n = struct.unpack('<I', data[80:84])[0]
tris = data[84:]
# second copy shifted far away in x
shifted = bytearray()
for i in range(n):
    rec = bytearray(tris[50*i:50*i+50])
    for k in range(3):
        off = 12 + 12*k
        x = struct.unpack('<f', rec[off:off+4])[0]
        rec[off:off+4] = struct.pack('<f', x + 100.0)
    shifted += rec
open(sys.argv[2], 'wb').write(data[:80] + struct.pack('<I', 2*n) + tris + bytes(shifted))
PY
check "two components refused" expect_exit 1 "2 connected components" "$VM" mesh "$T/two.stl" -o "$T/two.msh"
check "largest component" expect_exit 0 "wrote" "$VM" mesh "$T/two.stl" -o "$T/two.msh" --largest-component-only
check "largest component, older name" expect_exit 0 "wrote" "$VM" mesh "$T/two.stl" -o "$T/two-old.msh" --largest-component

# Voxel staircases: the raw marching cubes of a binary mask, smoothed by default.
check "phantom binary" expect_exit 0 "wrote" "$VM" phantom "$T/stair.stl" --kind tube --voxel 0.16 --binary
"$VM" info "$T/stair.stl" --json > "$T/stair.json"
check "info json staircase smoothed" [ "$(json "$T/stair.json" "d['smoothing']['mode'], d['smoothing']['staircase'], round(d['smoothing']['voxel'], 6), d['smoothing']['applied'], d['smoothing']['passes'] >= 24, 0 < d['smoothing']['max_displacement_voxels'] <= 0.5")" = "auto True 0.16 True True True" ]
check "info text staircase" expect_exit 0 "smoothing:   " "$VM" info "$T/stair.stl"
check "info warns smoothing" expect_exit 0 "the surface is a voxel staircase (voxel 0.16 $(json "$T/stair.json" "d['units']['unit']")): smoothed with" "$VM" info "$T/stair.stl"
check "info json smooth off" [ "$("$VM" info "$T/stair.stl" --smooth off --json | python3 -c "import json,sys; s=json.load(sys.stdin)['smoothing']; print(s['mode'], s['staircase'], s['applied'])")" = "off True False" ]
check "info json smooth passes" [ "$("$VM" info "$T/stair.stl" --smooth 3 --json | python3 -c "import json,sys; s=json.load(sys.stdin)['smoothing']; print(s['mode'], s['applied'], s['passes'])")" = "passes True 3" ]
check "noisy phantom not a staircase" [ "$(json "$T/info.json" "d['smoothing']['staircase'], d['smoothing']['applied']")" = "False False" ]
check "smooth 0 refused" expect_exit 2 "--smooth needs auto, off or a number of smoothing passes from 1 to 1000" "$VM" info "$T/stair.stl" --smooth 0
check "smooth x refused" expect_exit 2 "--smooth needs auto, off or a number" "$VM" mesh "$T/stair.stl" -o "$T/x.msh" --smooth x
check "binary is a phantom flag" expect_exit 2 "option '--binary' takes no value" "$VM" phantom "$T/x.stl" --binary=1

# Capped models, units, names and output formats.
check "phantom flat caps" expect_exit 0 "wrote" "$VM" phantom "$T/capped.stl" --kind bifurcation --voxel 0.12 --noise 0.3 --flat-caps
"$VM" info "$T/capped.stl" --json > "$T/capped.json"
check "caps become openings" [ "$(json "$T/capped.json" "[o['source'] for o in d['openings']], d['caps_removed'], d['closed']")" = "['cap', 'cap', 'cap'] 3 False" ]
check "info text says from a cap" expect_exit 0 "from a cap" "$VM" info "$T/capped.stl"
check "keep caps, clip off" [ "$("$VM" info "$T/capped.stl" --keep-caps --clip off --json | python3 -c "import json,sys; d=json.load(sys.stdin); print(len(d['openings']), d['closed'])")" = "0 True" ]
check "keep caps: the flat ends cut as blind ends" [ "$("$VM" info "$T/capped.stl" --keep-caps --json | python3 -c "import json,sys; d=json.load(sys.stdin); print([(o['source'], o['shape']) for o in d['openings']])")" = "[('clip', 'blind_end'), ('clip', 'blind_end'), ('clip', 'blind_end')]" ]
# Closed segmentations (rounded ends): cut open at their vessel ends, or by
# planes.
check "phantom closed" expect_exit 0 "wrote" "$VM" phantom "$T/closed.stl" --kind aneurysm --voxel 0.12 --noise 0.3 --no-open-ends
check "closed surface warned about" expect_exit 0 "3 vessel ends were found: cut them open with --clip auto (or give --clip-plane or --clip-at)" "$VM" info "$T/closed.stl" --clip off
check "info proposes the cuts" expect_exit 0 "vessel ends: 3 (the cuts --clip auto would make)" "$VM" info "$T/closed.stl" --clip off
# Each proposal is a --clip-plane that cuts one end open.
plane=$("$VM" info "$T/closed.stl" --clip off | sed -n 's/.*--clip-plane \([^ ]*\)$/\1/p' | head -1)
check "a proposed plane cuts one end" [ "$("$VM" info "$T/closed.stl" --clip-plane "$plane" --clip off --json | python3 -c "import json,sys; d=json.load(sys.stdin); print(len(d['openings']), d['openings'][0]['source'], d['openings'][0]['shape'], len(d['clip_proposals']))")" = "1 clip plane 2" ]
check "a plane given, then the blind ends left" [ "$("$VM" info "$T/closed.stl" --clip-plane "$plane" --json | python3 -c "import json,sys; d=json.load(sys.stdin); print(sorted(o['shape'] for o in d['openings']), len(d['clip_proposals']))")" = "['blind_end', 'blind_end', 'plane'] 0" ]
# --clip-at: across the vessel at the wall point nearest the one given.
at=$("$VM" info "$T/closed.stl" --clip off --json | python3 -c "import json,sys; p=json.load(sys.stdin)['clip_proposals'][0]; print(','.join(str(p['point'][k] - 2 * p['radius'] * p['normal'][k]) for k in range(3)))")
check "clip at a point cuts one end" expect_exit 0 "cut across the vessel at" "$VM" info "$T/closed.stl" --clip-at "$at"
check "clip at bad value" expect_exit 2 "--clip-at needs 3 numbers" "$VM" info "$T/closed.stl" --clip-at 1,2
"$VM" info "$T/closed.stl" --clip auto --json > "$T/clipped.json"
check "clip auto opens 3 ends" [ "$(json "$T/clipped.json" "[o['source'] for o in d['openings']], d['closed'], d['genus'], d['components']")" = "['clip', 'clip', 'clip'] False 0 1" ]
check "clip auto is the default" [ "$("$VM" info "$T/closed.stl" --json | python3 -c "import json,sys; d=json.load(sys.stdin); print([(o['source'], o['shape']) for o in d['openings']], d['closed'])")" = "[('clip', 'blind_end'), ('clip', 'blind_end'), ('clip', 'blind_end')] False" ]
check "clips reported" [ "$(json "$T/clipped.json" "len(d['clips']), all(c['radius'] > 0.4 and c['area_removed'] > 0 for c in d['clips'])")" = "3 True" ]
check "info text says from a clip" expect_exit 0 "from a clip" "$VM" info "$T/closed.stl" --clip auto --clip-distance 1.5
check "clip plane bad value" expect_exit 2 "--clip-plane needs 6 numbers" "$VM" info "$T/closed.stl" --clip-plane 1,2,3
check "clip plane zero normal" expect_exit 2 "--clip-plane needs 6 numbers" "$VM" info "$T/closed.stl" --clip-plane 0,0,0,0,0,0
check "clip bad value" expect_exit 2 "--clip needs off or auto" "$VM" info "$T/closed.stl" --clip sometimes
check "clip distance bad value" expect_exit 2 "--clip-distance needs a positive number" "$VM" info "$T/closed.stl" --clip auto --clip-distance 0
check "clip plane that misses" expect_exit 1 "the plane at (0, 30, 3) does not cut the surface within" "$VM" info "$T/closed.stl" --clip-plane 0,30,3,0,0,1
check "clip plane cuts one end" [ "$("$VM" info "$T/closed.stl" --clip-plane 0,0,-5.5,0,0,-1 --clip off --json | python3 -c "import json,sys; d=json.load(sys.stdin); print(len(d['openings']), d['openings'][0]['source'], round(d['openings'][0]['centroid'][2], 6))")" = "1 clip -5.5" ]
check "mesh clip auto" expect_exit 0 "wrote" "$VM" mesh "$T/closed.stl" --clip auto -o "$T/clipped.msh" --size 0.3 --layers 1 --verify --report "$T/clipped-report.json"
check "clipped groups" [ "$(json "$T/clipped-report.json" "','.join(g['name'] for g in d['output']['groups'])")" = "wall,inlet,outlet_1,outlet_2,lumen" ]
# Caps a repair tool makes (fans, domes) and a closed tree whose root is
# short and wide: each meshes with the default options.
check "phantom fan caps" expect_exit 0 "wrote" "$VM" phantom "$T/fans.stl" --kind bifurcation --voxel 0.15 --noise 0.3 --caps fan
check "phantom dome caps" expect_exit 0 "wrote" "$VM" phantom "$T/domes.stl" --kind bifurcation --voxel 0.1 --noise 0.1 --caps dome
check "phantom closed root (older name --closed)" expect_exit 0 "wrote" "$VM" phantom "$T/root.stl" --kind root --voxel 0.15 --noise 0.3 --closed
check "phantom caps bad value" expect_exit 2 "--caps needs flat, fan or dome" "$VM" phantom "$T/x.stl" --caps cone
check "fans become openings at their rims" [ "$("$VM" info "$T/fans.stl" --json | python3 -c "import json,sys; d=json.load(sys.stdin); print([(o['source'], o['shape']) for o in d['openings']], d['caps_removed'])")" = "[('cap', 'fan'), ('cap', 'fan'), ('cap', 'fan')] 3" ]
check "domes become openings at their rims" [ "$("$VM" info "$T/domes.stl" --json | python3 -c "import json,sys; d=json.load(sys.stdin); print([(o['source'], o['shape']) for o in d['openings']])")" = "[('cap', 'dome'), ('cap', 'dome'), ('cap', 'dome')]" ]
check "info says the caps' shapes" expect_exit 0 "3 caps were recognised and removed (0 planar, 3 fans, 0 domes)" "$VM" info "$T/fans.stl"
check "root: the widest opening, a short root" [ "$("$VM" info "$T/root.stl" --json | python3 -c "import json,sys; d=json.load(sys.stdin); o=d['openings']; print(len(o), o[0]['name'], o[0]['shape'], round(o[0]['radius'], 1))")" = "5 inlet blind_end 1.7" ]
check "info says the short root" expect_exit 0 "(a short, wide root)" "$VM" info "$T/root.stl"
check "root proposals with clip off" [ "$("$VM" info "$T/root.stl" --clip off --json | python3 -c "import json,sys; d=json.load(sys.stdin); print(len(d['clip_proposals']), sum(p['short_root'] for p in d['clip_proposals']))")" = "5 1" ]
for m in fans domes root; do
  check "mesh $m with default options" expect_exit 0 "wrote" "$VM" mesh "$T/$m.stl" -o "$T/$m.msh" --verify --report "$T/$m-report.json"
  check "$m groups" [ "$(json "$T/$m-report.json" "' '.join(g['name'] for g in d['output']['groups'] if not g['name'].startswith('outlet_')), any(g['name'] == 'outlet_1' for g in d['output']['groups'])")" = "wall inlet lumen True" ]
done
# Units from anatomy: a carotid-sized bifurcation (radius 3.5) is mm; the
# same a tenth as large is cm; an aorta with SimVascular's labelled caps
# (VTP) is cm; the unit is said on every run, guessed or given.
"$VM" phantom "$T/carotid.stl" --kind bifurcation --voxel 0.15 --scale 3.5 > /dev/null
"$VM" phantom "$T/carotid-cm.stl" --kind bifurcation --voxel 0.15 --scale 0.35 > /dev/null
check "carotid in mm" expect_exit 0 "units:       mm (guessed, likely: vessel radius 3." "$VM" info "$T/carotid.stl"
check "carotid in cm" expect_exit 0 "units:       cm (guessed, likely: vessel radius 0.3" "$VM" info "$T/carotid-cm.stl"
check "carotid in cm, the alternative said" expect_exit 0 "; if it is mm, say --units mm)" "$VM" info "$T/carotid-cm.stl"
check "phantom vtp with labelled caps" expect_exit 0 "wrote" "$VM" phantom "$T/aorta.vtp" --kind bifurcation --voxel 0.15 --scale 1.2 --flat-caps
check "aorta vtp: caps from ModelFaceID" [ "$("$VM" info "$T/aorta.vtp" --json | python3 -c "import json,sys; d=json.load(sys.stdin); print(d['label_array'], d['caps_removed'], sorted(o['label'] for o in d['openings']))")" = "ModelFaceID 3 [2, 3, 4]" ]
check "aorta vtp: cm from the labels" expect_exit 0 "units:       cm (guessed, unsure: " "$VM" info "$T/aorta.vtp"
check "aorta vtp: the labels said" expect_exit 0 "the face labels (ModelFaceID) hint at cm" "$VM" info "$T/aorta.vtp"
"$VM" info "$T/aorta.vtp" --json > "$T/aorta.json"
check "aorta vtp: the analysis says what to ask" [ "$(json "$T/aorta.json" "d['units']['unit'], d['units']['guessed'], d['units']['certain'], d['units']['confidence'], d['units']['alternative'], d['units']['measures']['label_array']")" = "cm True False unsure mm ModelFaceID" ]
check "mesh says the unit" expect_exit 0 "units: cm (guessed, unsure: " "$VM" mesh "$T/aorta.vtp" -o "$T/aorta.msh" --size 0.4 --surface-only
check "mesh says a given unit" expect_exit 0 "units: mm (given)" "$VM" mesh "$T/aorta.vtp" -o "$T/aorta.msh" --size 0.4 --surface-only --units mm
check "mesh --quiet says nothing" [ -z "$("$VM" mesh "$T/aorta.vtp" -o "$T/aorta.msh" --size 0.4 --surface-only --quiet 2>/dev/null)" ]
check "units given" [ "$("$VM" info "$T/bif.stl" --units cm --json | python3 -c "import json,sys; u=json.load(sys.stdin)['units']; print(u['unit'], u['guessed'], u['certain'], u['confidence'], repr(u['reason']), repr(u['alternative']))")" = "cm False True certain '' ''" ]
check "bad units" expect_exit 2 "--units needs mm, cm or m" "$VM" info "$T/bif.stl" --units inch
"$VM" phantom "$T/small.stl" --kind tube --voxel 0.2 --scale 0.002 > /dev/null
check "metres guessed" expect_exit 0 "units:       m (guessed, certain: " "$VM" info "$T/small.stl"
check "mesh named capped" expect_exit 0 "wrote" "$VM" mesh "$T/capped.stl" -o "$T/capped.msh" --size 0.3 --layers 2 --name 2=left --name 1=aorta --report "$T/capped-report.json"
check "named groups" [ "$(json "$T/capped-report.json" "sorted(g['name'] for g in d['output']['groups'])")" = "['aorta', 'left', 'lumen', 'outlet_1', 'wall']" ]
check "name reserved" expect_exit 2 "--name cannot be 'lumen'" "$VM" mesh "$T/capped.stl" -o "$T/x.msh" --name 1=lumen
check "name invalid" expect_exit 2 "--name needs K=NAME with NAME 1-64 letters" "$VM" mesh "$T/capped.stl" -o "$T/x.msh" --name 1=9lives
check "name without K" expect_exit 2 "--name needs K=VALUE" "$VM" mesh "$T/capped.stl" -o "$T/x.msh" --name left
check "name out of range" expect_exit 2 "--name names opening 5, but there are 3 openings" "$VM" mesh "$T/capped.stl" -o "$T/x.msh" --name 5=x
check "name twice" expect_exit 2 "--name gives 'a' to openings 1 and 2" "$VM" mesh "$T/capped.stl" -o "$T/x.msh" --name 1=a --name 2=a
for f in vtu vtp stl zip; do
  check "mesh to .$f" expect_exit 0 "wrote" "$VM" mesh "$T/bif.stl" -o "$T/out.$f" --size 0.3 --layers 1
done
check "mesh-complete folder" expect_exit 0 "wrote" "$VM" mesh "$T/bif.stl" -o "$T/mc/" --size 0.3 --layers 1
check "mesh-complete files" [ -f "$T/mc/mesh-complete.mesh.vtu" -a -f "$T/mc/mesh-complete.exterior.vtp" -a -f "$T/mc/mesh-surfaces/outlet_2.vtp" -a -f "$T/mc/mesh-complete.names.json" ]
check "zip is valid" python3 -m zipfile -t "$T/out.zip"
check "openfoam case folder" expect_exit 0 "wrote" "$VM" mesh "$T/bif.stl" -o "$T/of/" --format foam --size 0.3 --layers 1 --prisms
check "openfoam case files" [ -f "$T/of/constant/polyMesh/points" -a -f "$T/of/constant/polyMesh/faces" -a -f "$T/of/constant/polyMesh/owner" -a -f "$T/of/constant/polyMesh/neighbour" -a -f "$T/of/constant/polyMesh/boundary" -a -f "$T/of/constant/polyMesh/cellZones" -a -f "$T/of/system/controlDict" -a -f "$T/of/case.foam" ]
check "openfoam wall patch" grep -q "type            wall;" "$T/of/constant/polyMesh/boundary"
check "openfoam by .foam" expect_exit 0 "wrote" "$VM" mesh "$T/bif.stl" -o "$T/of2/bif.foam" --size 0.3 --layers 1
check "openfoam .foam marker and case" [ -f "$T/of2/bif.foam" -a ! -s "$T/of2/bif.foam" -a -f "$T/of2/constant/polyMesh/faces" -a ! -e "$T/of2/case.foam" ]
echo "// the user's own" >> "$T/of/system/controlDict"
echo "stale" > "$T/of/constant/polyMesh/faceZones"
check "an existing OpenFOAM case folder gets its polyMesh" expect_exit 0 "wrote" "$VM" mesh "$T/bif.stl" -o "$T/of" --size 0.3 --layers 1
check "the case's mesh replaced, its settings kept" [ "$(find "$T/of/constant/polyMesh/faces" -newer "$T/of2/bif.foam" | wc -l)" = 1 -a ! -e "$T/of/mesh-complete.mesh.vtu" -a "$(tail -1 "$T/of/system/controlDict")" = "// the user's own" -a ! -e "$T/of/constant/polyMesh/faceZones" ]
check "openfoam zipped" expect_exit 0 "wrote" "$VM" mesh "$T/bif.stl" -o "$T/of.zip" --format foam --size 0.3 --layers 1
check "openfoam zip holds the case" python3 -c "import zipfile, sys; n = zipfile.ZipFile('$T/of.zip').namelist(); sys.exit(0 if 'constant/polyMesh/boundary' in n and 'case.foam' in n else 1)"
# OpenFOAM binary (--foam-binary): points, faces (faceCompactList), owner
# and neighbour as raw little-endian lists; checkMesh (when installed) reads
# the same mesh as from the text case.
check "openfoam binary case" expect_exit 0 "wrote" "$VM" mesh "$T/bif.stl" -o "$T/ofb/" --format foam --size 0.3 --layers 1 --prisms --foam-binary
check "openfoam binary: faces a faceCompactList" grep -aq "^    class       faceCompactList;" "$T/ofb/constant/polyMesh/faces"
check "openfoam binary: points, 3 doubles a point" [ "$(/usr/bin/python3 -c "
b = open('$T/ofb/constant/polyMesh/points', 'rb').read()
at = b.index(b'\\n}\\n') + 3
n, rest = b[at:].lstrip(b'\\n').split(b'\\n', 1)
print(b'format      binary;' in b and rest[:1] == b'(' and rest[1 + 24 * int(n):1 + 24 * int(n) + 2] == b')\\n')")" = True ]
if [[ -f /usr/share/openfoam/etc/bashrc ]] && command -v checkMesh > /dev/null; then
  "$VM" mesh "$T/bif.stl" -o "$T/ofa/" --format foam --size 0.3 --layers 1 --prisms > /dev/null
  foam_counts() {  # the mesh's counts as checkMesh reads them, and its verdict
    bash -c "source /usr/share/openfoam/etc/bashrc > /dev/null 2>&1; checkMesh -case '$1'" 2>&1 |
      grep -E "^ +(points|faces|internal faces|cells|prisms|tetrahedra): |^Mesh OK"
  }
  ascii_counts=$(foam_counts "$T/ofa")
  check "checkMesh reads the binary case as the text one" [ -n "$ascii_counts" -a "$(foam_counts "$T/ofb")" = "$ascii_counts" -a "$(printf '%s\n' "$ascii_counts" | tail -n 1)" = "Mesh OK." ]
else
  echo "note: OpenFOAM not installed; checkMesh on the binary case skipped"
fi
check "unknown extension" expect_exit 2 "cannot tell the output format from" "$VM" mesh "$T/bif.stl" -o "$T/out.xyz"
check "volume format needs a volume" expect_exit 2 "--format cannot be vtu: it holds a volume mesh, and --surface-only writes the wall alone" "$VM" mesh "$T/bif.stl" -o "$T/out.vtu" --surface-only
check "format option wins" expect_exit 0 "wrote" "$VM" mesh "$T/bif.stl" -o "$T/wall.dat" --format stl --surface-only --size 0.3
check "provenance in msh" grep -q "^vesselmesh .*; input xxh128:[0-9a-f]\{32\}; options: size=0.3" "$T/capped.msh"
"$VM" mesh "$T/bif.stl" -o "$T/m.msh" --size 0.3 --layers 0 --surface-only --output-units m --units mm > /dev/null
check "output units convert" [ "$(python3 -c "
lines = open('$T/m.msh').read().split('\n')
box = [abs(float(x)) for x in lines[lines.index('\$Entities') + 2].split()[1:7]]
print(0.001 < max(box) < 0.02)")" = True ]
if [[ -x /usr/bin/python3 ]] && /usr/bin/python3 -c "import vtk, meshio" 2>/dev/null; then
  "$VM" mesh "$T/bif.stl" -o "$T/same.msh" --size 0.3 --layers 1 > /dev/null
  check "VTK and meshio read our VTU/VTP/mesh-complete" /usr/bin/python3 "$(dirname "$0")/../../validation/check_vtk_outputs.py" --msh "$T/same.msh" --vtu "$T/out.vtu" --vtp "$T/out.vtp" --mesh-complete "$T/out.zip"
fi
# Compressed VTK (--vtk-compress): the same VTU and VTP in VTK's zlib
# blocks, under a third of the bytes; VTK and meshio read the same mesh.
for f in vtu vtp; do
  check "mesh to compressed .$f" expect_exit 0 "wrote" "$VM" mesh "$T/bif.stl" -o "$T/outz.$f" --size 0.3 --layers 1 --vtk-compress
  check "compressed .$f: zlib blocks, smaller" [ "$(head -c 300 "$T/outz.$f" | grep -c 'header_type="UInt64" compressor="vtkZLibDataCompressor"')" = 1 -a $(($(stat -c %s "$T/outz.$f") * 2)) -lt "$(stat -c %s "$T/out.$f")" ]
done
if [[ -x /usr/bin/python3 ]] && /usr/bin/python3 -c "import vtk, meshio" 2>/dev/null; then
  check "VTK and meshio read the compressed VTU/VTP" /usr/bin/python3 "$(dirname "$0")/../../validation/check_vtk_outputs.py" --msh "$T/same.msh" --vtu "$T/outz.vtu" --vtp "$T/outz.vtp"
  check "meshio: the compressed VTU's arrays are the raw one's" /usr/bin/python3 -c "
import sys, meshio, numpy as np
a, b = meshio.read('$T/out.vtu'), meshio.read('$T/outz.vtu')
same = np.array_equal(a.points, b.points) and len(a.cells) == len(b.cells) > 0 and all(
    x.type == y.type and np.array_equal(x.data, y.data) for x, y in zip(a.cells, b.cells)) and all(
    np.array_equal(a.cell_data[k][0], b.cell_data[k][0]) for k in ('ModelRegionID', 'GlobalElementID'))
sys.exit(0 if same else 1)"
fi

# Flow extensions: each opening moved out along its normal by L radii.
"$VM" info "$T/bif.stl" --flow-extension 4 --json > "$T/ext.json"
check "flow extension moves the openings" [ "$(python3 -c "
import json, math
a, b = json.load(open('$T/info.json')), json.load(open('$T/ext.json'))
ok = len(a['openings']) == len(b['openings']) == 3
for o, e in zip(a['openings'], b['openings']):
    moved = [e['centroid'][k] - o['centroid'][k] for k in range(3)]
    want = [4 * o['radius'] * o['normal'][k] for k in range(3)]
    ok = ok and math.dist(moved, want) < 1e-6 * o['radius'] and abs(e['extension'] - 4 * o['radius']) < 1e-9
print(ok)")" = True ]
check "flow extension per opening" expect_exit 0 "flow extensions added at opening 2" "$VM" info "$T/bif.stl" --flow-extension 2=3
check "flow extension bad" expect_exit 2 "--flow-extension needs a length in local radii" "$VM" info "$T/bif.stl" --flow-extension -1
check "flow extension opening out of range" expect_exit 2 "--flow-extension names opening 9, but there are 3 openings" "$VM" info "$T/bif.stl" --flow-extension 9=2
check "mesh with flow extensions" expect_exit 0 "wrote" "$VM" mesh "$T/bif.stl" -o "$T/ext.msh" --flow-extension 3 --size 0.3 --layers 2 --verify

# Outliers: a stray triangle a million units away is removed (not welded
# into the vessel).
python3 - "$T/bif.stl" "$T/stray.stl" <<'PY'
import struct, sys
d = open(sys.argv[1], 'rb').read()
n = struct.unpack('<I', d[80:84])[0]
stray = struct.pack('<12fH', 0, 0, 1, 1e6, 0, 0, 1e6 + 1, 0, 0, 1e6, 1, 0, 0)
open(sys.argv[2], 'wb').write(d[:80] + struct.pack('<I', n + 1) + d[84:] + stray)
PY
check "stray triangle removed" expect_exit 0 "removed a small separate piece (1 triangle, under 1% of the surface) at (1e+06, 0, 0)" "$VM" info "$T/stray.stl"
check "stray triangle: the vessel kept" [ "$("$VM" info "$T/stray.stl" --json | python3 -c "import json,sys; d=json.load(sys.stdin); print(d['components'], d['specks_removed'], len(d['openings']), d['bounding_box']['max'][0] < 10)")" = "1 1 3 True" ]

# The element budget: absurd sizes are refused before meshing, naming the option.
check "tiny size refused" expect_exit 2 "--size makes about" "$VM" mesh "$T/bif.stl" -o "$T/x.msh" --size 1e-30
check "tiny size refused, surface only" expect_exit 2 "triangles on the wall, more than the element budget (--max-elements 15000000)" "$VM" mesh "$T/bif.stl" -o "$T/x.msh" --size 1e-30 --surface-only
check "huge N refused" expect_exit 2 "--per-circumference makes about" "$VM" mesh "$T/bif.stl" -o "$T/x.msh" --per-circumference 1e6
check "tiny core refused" expect_exit 2 "--core-size makes about" "$VM" mesh "$T/bif.stl" -o "$T/x.msh" --core-size 1e-4
check "coarse size refused" expect_exit 2 "--size 5 makes a wall that encloses" "$VM" mesh "$T/bif.stl" -o "$T/x.msh" --size 5 --layers 0
check "coarse size accepted when asked" expect_exit 0 "wrote" "$VM" mesh "$T/bif.stl" -o "$T/x.msh" --size 5 --surface-only --max-volume-change 1
check "volume change printed" expect_exit 0 "of the input's" "$VM" mesh "$T/bif.stl" -o "$T/x.msh" --surface-only
check "budget option" expect_exit 2 "--max-elements needs" "$VM" mesh "$T/bif.stl" -o "$T/x.msh" --max-elements 10
# The default size never refuses on the budget: it is coarsened, and said.
check "default coarsened to the budget" expect_exit 0 "warning: the default size (--per-circumference 20) would make about" "$VM" mesh "$T/bif.stl" -o "$T/x.msh" --max-elements 15000 --report "$T/budget.json"
check "coarsening reported" [ "$(json "$T/budget.json" "d['element_budget']['coarsened'], d['element_budget']['asked_per_circumference'], 13 <= d['element_budget']['per_circumference'] < 20, d['element_budget']['elements'] <= 15000 < d['element_budget']['asked_elements']")" = "True 20 True True" ]
check "coarsening says how to ask for the finer mesh" expect_exit 0 "ask for the finer mesh with --per-circumference 20 and --max-elements" "$VM" mesh "$T/bif.stl" -o "$T/x.msh" --max-elements 15000
check "a given size still refused, with the one that fits" expect_exit 2 "--per-circumference makes about" "$VM" mesh "$T/bif.stl" -o "$T/x.msh" --max-elements 15000 --per-circumference 20
fitting=$("$VM" mesh "$T/bif.stl" -o "$T/x.msh" --max-elements 15000 --per-circumference 20 2>&1 | sed -n 's/.*(--per-circumference \([0-9.]*\) fits).*/\1/p')
check "the size that fits fits" expect_exit 0 "wrote" "$VM" mesh "$T/bif.stl" -o "$T/x.msh" --max-elements 15000 --per-circumference "$fitting"
check "a budget too small for the default" expect_exit 2 "--max-elements 1000 is too small for this model" "$VM" mesh "$T/bif.stl" -o "$T/x.msh" --max-elements 1000
# A surface that encloses no volume (a flat disk) is refused as such.
python3 - "$T/disk.stl" <<'PY'
import math, struct, sys
n, tris = 24, []
ring = lambda r, i: (r * math.cos(2 * math.pi * i / n), r * math.sin(2 * math.pi * i / n), 0.0)
for i in range(n):
    tris.append(((0, 0, 0), ring(5, i), ring(5, i + 1)))
    tris += [(ring(5, i), ring(10, i), ring(10, i + 1)), (ring(5, i), ring(10, i + 1), ring(5, i + 1))]
with open(sys.argv[1], "wb") as f:
    f.write(b"disk".ljust(80, b" ") + struct.pack("<I", len(tris)))
    for t in tris:
        f.write(struct.pack("<12fH", 0, 0, 0, *t[0], *t[1], *t[2], 0))
PY
check "a disk encloses no volume (info)" expect_exit 0 "warning: the surface encloses no volume: it is a single sheet" "$VM" info "$T/disk.stl"
check "a disk is refused as such" expect_exit 1 "cannot mesh: the surface encloses no volume: it is a single sheet (a flat disk, one side of a wall)" "$VM" mesh "$T/disk.stl" -o "$T/x.msh"

# Gmsh reads both versions: the named groups, the element counts of the
# report, and no inverted tetrahedron (signed volumes from the nodes).
check "report volume groups" [ "$(json "$T/report.json" "','.join(g['name'] for g in d['output']['groups'])")" = "wall,inlet,outlet_1,outlet_2,lumen" ]
check "mesh surface-only writes the wall" [ "$(json "$T/u.json" "[g['name'] for g in d['output']['groups']]")" = "['wall']" ]
if /usr/bin/python3 -c "import gmsh" 2>/dev/null; then
  want=$(json "$T/report.json" "'%d %d' % (d['output']['volume']['boundary_triangles'], d['output']['volume']['tetrahedra'])")
  for f in bif41 bif22; do
    got=$(/usr/bin/python3 - "$T/$f.msh" <<'PY'
import sys, gmsh, numpy as np
gmsh.initialize()
gmsh.option.setNumber("General.Verbosity", 0)
gmsh.open(sys.argv[1])
names = [gmsh.model.getPhysicalName(d, t) for d, t in gmsh.model.getPhysicalGroups()]
tags, coords, _ = gmsh.model.mesh.getNodes()
xyz = np.zeros((int(tags.max()) + 1, 3))
xyz[tags.astype(int)] = coords.reshape(-1, 3)
ntri = ntet = 0
vmin = 1.0
for dim in (2, 3):
    for ty, _, nodes in zip(*gmsh.model.mesh.getElements(dim)):
        if ty == 2:
            ntri += len(nodes) // 3
        if ty == 4:
            t = nodes.astype(int).reshape(-1, 4)
            a, b, c, e = (xyz[t[:, k]] for k in range(4))
            v = np.einsum("ij,ij->i", np.cross(b - a, c - a), e - a)
            ntet += len(t)
            vmin = min(vmin, v.min())
print(ntri, ntet, ",".join(names), "positive" if vmin > 0 else "INVERTED")
gmsh.finalize()
PY
)
    got=$(printf '%s\n' "$got" | tail -n 1)
    check "gmsh reads $f" [ "$got" = "$want wall,inlet,outlet_1,outlet_2,lumen positive" ]
  done
else
  echo "note: gmsh Python API not installed; Gmsh read check skipped"
fi

# MSH 4.1 binary (--msh-binary): the text file's mesh in Gmsh's binary
# layout; refused with MSH 2.2, asked or the openfoam preset's, before
# anything is read.
"$VM" phantom "$T/tube.stl" --kind tube --voxel 0.2 > /dev/null
check "mesh --msh-binary" expect_exit 0 "wrote" "$VM" mesh "$T/tube.stl" -o "$T/tubeb.msh" --size 0.4 --layers 1 --msh-binary
check "mesh the same as text" expect_exit 0 "wrote" "$VM" mesh "$T/tube.stl" -o "$T/tubea.msh" --size 0.4 --layers 1
check "msh binary header, the int 1 little-endian" cmp -n 40 "$T/tubeb.msh" <(printf '$MeshFormat\n4.1 1 8\n\001\000\000\000\n$EndMeshFormat\n')
check "--msh-binary with 2.2 refused" expect_exit 2 "--msh-binary writes MSH 4.1 only" "$VM" mesh "$T/none.stl" -o "$T/x.msh" --msh-binary --msh-version 2.2
check "--msh-binary with the openfoam preset refused" expect_exit 2 "give --msh-version 4.1, or drop --msh-binary" "$VM" mesh "$T/none.stl" -o "$T/x.msh" --msh-binary --solver openfoam
if /usr/bin/python3 -c "import gmsh" 2>/dev/null; then
  same=$(/usr/bin/python3 - "$T/tubea.msh" "$T/tubeb.msh" <<'PY'
import sys, gmsh, numpy as np
def read(path):
    gmsh.initialize()
    gmsh.option.setNumber("General.Verbosity", 0)
    gmsh.open(path)
    tags, coords, _ = gmsh.model.mesh.getNodes()
    elements = [(dim, int(ty), list(tags_), list(nodes)) for dim in (2, 3)
                for ty, tags_, nodes in zip(*gmsh.model.mesh.getElements(dim))]
    groups = [(d, t, gmsh.model.getPhysicalName(d, t), list(gmsh.model.getEntitiesForPhysicalGroup(d, t)))
              for d, t in gmsh.model.getPhysicalGroups()]
    gmsh.finalize()
    return list(tags), coords.tolist(), elements, groups
text, binary = read(sys.argv[1]), read(sys.argv[2])
print("same" if text == binary and len(text[0]) > 0 else "DIFFERENT")
PY
)
  check "gmsh reads the binary file as the text one (nodes, elements, groups)" [ "$(printf '%s\n' "$same" | tail -n 1)" = same ]
fi

# A mesh-independence family: three meshes of one surface, refined by 1.4,
# with their table; the methods report beside it.
check "family" expect_exit 0 "family: 3 meshes, ratio 1.4, layers refine" "$VM" mesh "$T/bif.stl" -o "$T/fam.msh" --per-circumference 10 --layers 2 --family 3 --report-html "$T/fam.html"
check "family: three files and the table" [ -s "$T/fam_0.msh" -a -s "$T/fam_1.msh" -a -s "$T/fam_2.msh" -a -s "$T/fam_family.csv" -a -s "$T/fam_family.json" ]
check "family: the achieved ratios are within 10% of r, h decreasing" [ "$(json "$T/fam_family.json" "all(abs(r['ratio'] - 1.4) < 0.14 for r in d['rows'][1:]) and d['rows'][0]['file'].endswith('fam_0.msh') and len(d['rows']) == 3")" = True ]
check "family: the CSV has a row per member" [ "$(wc -l < "$T/fam_family.csv")" -eq 4 ]
check "family: the members' provenance says which" grep -q "family_member=2" "$T/fam_2.msh"
check "family: the report is offline and has the table" [ "$(python3 -c "import sys; h=open(sys.argv[1]).read(); print('<script' not in h and 'http://' not in h and 'https://' not in h and 'fam_2.msh' in h and 'data:image/png;base64,' in h)" "$T/fam.html")" = True ]
check "family: bad count" expect_exit 2 "--family needs a number of meshes from 1 (one mesh) to 6" "$VM" mesh "$T/bif.stl" -o "$T/x.msh" --family 9
check "family: bad ratio" expect_exit 2 "--ratio needs a refinement ratio from 1.1 to 2" "$VM" mesh "$T/bif.stl" -o "$T/x.msh" --family 2 --ratio 1
check "family: surface only refused" expect_exit 2 "--family makes volume meshes" "$VM" mesh "$T/bif.stl" -o "$T/x.stl" --family 2 --surface-only
check "family: folders for mesh-complete" expect_exit 0 "wrote $T/famc_1/" "$VM" mesh "$T/bif.stl" -o "$T/famc/" --per-circumference 10 --layers 1 --family 2 --format mesh-complete
check "family: mesh-complete member folders" [ -d "$T/famc_0" -a -d "$T/famc_1" -a -s "$T/famc_family.csv" ]
check "report-html of one mesh" expect_exit 0 "wrote" "$VM" mesh "$T/bif.stl" -o "$T/one.msh" --per-circumference 10 --layers 2 --report-html "$T/one.html"
check "report-html: the groups, no family" [ "$(python3 -c "import sys; h=open(sys.argv[1]).read(); print('lang=\"en\"' in h and 'outlet_2' in h and 'lumen' in h and 'fam_' not in h)" "$T/one.html")" = True ]
check "report-html: an unwritable path" expect_exit 1 "cannot write" "$VM" mesh "$T/bif.stl" -o "$T/one2.msh" --per-circumference 10 --layers 0 --report-html "$T/nodir/r.html"

echo "$passes passed, $failures failed"
[[ $failures -eq 0 ]]
