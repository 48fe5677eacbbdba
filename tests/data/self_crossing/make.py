#!/usr/bin/env python3
"""Writes the self-crossing test files (run from this directory):

  one.obj    two UV spheres joined into one shell by a tube from the first's
             far side (-x) to the second's (+x), through both: one shell that
             crosses itself;
  three.obj  the same as three separate closed shells: the spheres and the
             tube closed by the two faces it replaces, reversed.

As 2-chains one.obj = three.obj, so both bound the same solid {W >= 1}
(tests/boolean/self_solid_test.cpp explains the identity)."""
import math


def uv_sphere(rings, segments, r, c):
    v = [(c[0], c[1], c[2] + r)]
    for i in range(1, rings):
        th = math.pi * i / rings
        for j in range(segments):
            ph = 2 * math.pi * j / segments
            v.append((c[0] + r * math.sin(th) * math.cos(ph), c[1] + r * math.sin(th) * math.sin(ph),
                      c[2] + r * math.cos(th)))
    south = len(v)
    v.append((c[0], c[1], c[2] - r))
    at = lambda i, j: 1 + (i - 1) * segments + j % segments
    f = [(0, at(1, j), at(1, j + 1)) for j in range(segments)]
    for i in range(1, rings - 1):
        for j in range(segments):
            f.append((at(i, j), at(i + 1, j), at(i + 1, j + 1)))
            f.append((at(i, j), at(i + 1, j + 1), at(i, j + 1)))
    f += [(south, at(rings - 1, j + 1), at(rings - 1, j)) for j in range(segments)]
    return v, f


def extreme(v, f, sign):
    return max(range(len(f)), key=lambda k: sign * sum(v[i][0] for i in f[k]))


def walls(a, b):
    partner = lambda i: b[(3 - i) % 3]
    out = []
    for i in range(3):
        p, q, r, s = a[i], a[(i + 1) % 3], partner((i + 1) % 3), partner(i)
        out += [(p, q, r), (p, r, s)]
    return out


def obj_text(v, f):
    return "".join("v %r %r %r\n" % p for p in v) + "".join("f %d %d %d\n" % tuple(i + 1 for i in t) for t in f)


def write(name, v, f):
    with open(name, "w") as out:
        out.write(obj_text(v, f))


def joined(rings_a, rings_b):
    """(vertices, faces) of the one shell and of the three shells."""
    va, fa = uv_sphere(rings_a, 2 * rings_a, 1.0, (0.0, 0.0, 0.0))
    vb, fb = uv_sphere(rings_b, 2 * rings_b, 0.8, (0.9, 0.0625, 0.03125))
    ka, kb = extreme(va, fa, -1), extreme(vb, fb, +1)
    n = len(va)
    one_v = va + vb
    one_f = [t for k, t in enumerate(fa) if k != ka] + [tuple(i + n for i in t) for k, t in enumerate(fb) if k != kb]
    one_f += walls(fa[ka], tuple(i + n for i in fb[kb]))
    three_v = va + vb
    three_f = fa + [tuple(i + n for i in t) for t in fb]
    m = len(three_v)
    three_v += [va[i] for i in fa[ka]] + [vb[i] for i in fb[kb]]
    ta, tb = (m, m + 1, m + 2), (m + 3, m + 4, m + 5)
    three_f += walls(ta, tb) + [(ta[0], ta[2], ta[1]), (tb[0], tb[2], tb[1])]
    return (one_v, one_f), (three_v, three_f)


if __name__ == "__main__":
    one, three = joined(8, 7)
    write("one.obj", *one)
    write("three.obj", *three)
