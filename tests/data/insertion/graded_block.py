#!/usr/bin/python3
# Writes graded_block.msh (Gmsh MSH 2.2, ASCII, um): a 3000 x 3000 x 1150 um block of 6 right-handed tetrahedra per
# hex, graded towards the insertion site (0, 0) on the top z = 0, for deterministic complete-insertion tests (Gmsh's
# own mesher is not run-to-run deterministic). Run: /usr/bin/python3 graded_block.py
import itertools

xy = [-1500, -800, -400, -200, -100, -50, -25, 0, 25, 50, 100, 200, 400, 800, 1500]
z = [0, -25, -50, -100, -200, -450, -1150]
index = {}
nodes = []
for k, zk in enumerate(z):
    for j, yj in enumerate(xy):
        for i, xi in enumerate(xy):
            index[i, j, k] = len(nodes) + 1
            nodes.append((xi, yj, zk))

def volume(a, b, c, d):
    u = [b[t] - a[t] for t in range(3)]
    v = [c[t] - a[t] for t in range(3)]
    w = [d[t] - a[t] for t in range(3)]
    return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]))

tets = []
n = len(xy) - 1
for i, j, k in itertools.product(range(n), range(n), range(len(z) - 1)):
    corner = lambda a, b, c: index[i + a, j + b, k + c]
    # Kuhn split along the diagonal (0,0,0)-(1,1,1): one tetrahedron per permutation of the axes.
    for order in itertools.permutations(range(3)):
        step = [0, 0, 0]
        path = [corner(0, 0, 0)]
        for axis in order:
            step[axis] = 1
            path.append(corner(*step))
        p = [nodes[t - 1] for t in path]
        if volume(*p) < 0:
            path[2], path[3] = path[3], path[2]
        tets.append(path)

with open("graded_block.msh", "w") as out:
    out.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n%d\n" % len(nodes))
    for t, p in enumerate(nodes, 1):
        out.write("%d %g %g %g\n" % (t, *p))
    out.write("$EndNodes\n$Elements\n%d\n" % len(tets))
    for e, t in enumerate(tets, 1):
        out.write("%d 4 2 1 1 %d %d %d %d\n" % (e, *t))
    out.write("$EndElements\n")
