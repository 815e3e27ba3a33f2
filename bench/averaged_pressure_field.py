"""Where the averaged-pressure law's disc sits in one step of `needlekit indent --out` (docs/indentation.md,
"Averaged pressure under friction"): reads a tissue step STEP.vtu (raw appended, linear tetrahedra, the block's top
at its highest z), lumps each top triangle's area A/3 to its corners (fem/boundary_conditions.cpp) and prints, per
material length l, p̄_l = max over contact nodes c of sum F_i / sum A_i over the contact nodes within l of c (the law
of include/needlekit/insertion/averaged_contact_pressure.hpp, with F_i = contact_pressure_Pa * A_i), the disc's centre
and how many nodes it holds; then the contact nodes by distance from the axis.

    python3 bench/averaged_pressure_field.py OUT/NAME_step_016.vtu 25 50 100
"""
import math
import re
import struct
import sys

FORMATS = {"Float64": "d", "Int64": "q", "UInt8": "B"}


def read_vtu(path):
    raw = open(path, "rb").read()
    head, _, rest = raw.partition(b'<AppendedData encoding="raw">')
    data = rest[rest.index(b"_") + 1:]
    arrays = {}
    pattern = rb'<DataArray type="(\w+)" Name="(\w+)" NumberOfComponents="(\d+)" format="appended" offset="(\d+)"'
    for m in re.finditer(pattern, head):
        kind, name, components, offset = m.group(1).decode(), m.group(2).decode(), int(m.group(3)), int(m.group(4))
        nbytes = struct.unpack_from("<Q", data, offset)[0]  # header_type="UInt64"
        code = FORMATS[kind]
        values = struct.unpack_from("<%d%s" % (nbytes // struct.calcsize(code), code), data, offset + 8)
        arrays[name] = [values[i:i + components] for i in range(0, len(values), components)] if components > 1 \
            else list(values)
    return arrays


def top_node_areas(points, connectivity, offsets):
    top = max(p[2] for p in points)
    on_top = [abs(p[2] - top) < 1e-9 for p in points]
    faces = {}
    start = 0
    for end in offsets:
        tet = connectivity[start:end][:4]
        start = end
        for face in ((0, 1, 2), (0, 1, 3), (0, 2, 3), (1, 2, 3)):
            triangle = tuple(sorted(tet[i] for i in face))
            if all(on_top[i] for i in triangle):
                faces[triangle] = faces.get(triangle, 0) + 1
    area = [0.0] * len(points)
    for triangle, count in faces.items():
        if count != 1:
            continue  # an inner face lying in the top plane
        p, q, r = (points[i] for i in triangle)
        a = 0.5 * abs((q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]))
        for i in triangle:
            area[i] += a / 3
    return area


def main(path, lengths_um):
    f = read_vtu(path)
    points = f["Points"]
    area = top_node_areas(points, f["connectivity"], f["offsets"])
    pressure = f["contact_pressure_Pa"]
    contact = [i for i, flag in enumerate(f["contact_flag"]) if flag > 0]
    print(f"{path}: {len(contact)} contact nodes")
    for l in (x * 1e-6 for x in lengths_um):
        best, centre, held = 0.0, None, 0
        for c in contact:
            inside = [i for i in contact if math.dist(points[i], points[c]) <= l]
            a = sum(area[i] for i in inside)
            if a > 0 and sum(pressure[i] * area[i] for i in inside) / a > best:
                best, centre, held = sum(pressure[i] * area[i] for i in inside) / a, c, len(inside)
        if centre is not None:
            x, y = points[centre][0] * 1e6, points[centre][1] * 1e6
            print(f"  l = {l * 1e6:g} um: p̄_l = {best / 1e6:.3f} MPa, disc at ({x:.0f}, {y:.0f}) um "
                  f"(r = {math.hypot(x, y):.0f} um), {held} nodes in it")
    print("  contact nodes (r um: p MPa, A um2):")
    for r, p, a in sorted((math.hypot(*points[i][:2]) * 1e6, pressure[i] / 1e6, area[i] * 1e12) for i in contact):
        print(f"    {r:.0f}: {p:.2f}, {a:.0f}")


if __name__ == "__main__":
    main(sys.argv[1], [float(x) for x in sys.argv[2:]])
