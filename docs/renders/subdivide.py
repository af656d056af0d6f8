#!/usr/bin/env python3
"""subdivide.py IN.obj OUT.obj [times]: split every face (triangulated fan) in four at its
edge midpoints, positions and UVs alike; objects kept."""
import sys
src, dst = sys.argv[1], sys.argv[2]; times = int(sys.argv[3]) if len(sys.argv) > 3 else 1
V, VT, objs = [], [], []  # objs: [name, [(vi, ti) triangles]]
cur = ['default', []]
for line in open(src):
    p = line.split()
    if not p: continue
    if p[0] == 'v': V.append(tuple(map(float, p[1:4])))
    elif p[0] == 'vt': VT.append(tuple(map(float, p[1:3])))
    elif p[0] in ('o', 'g'):
        if cur[1]: objs.append(cur)
        cur = [p[1] if len(p) > 1 else 'x', []]
    elif p[0] == 'f':
        c = []
        for w in p[1:]:
            s = w.split('/')
            vi = int(s[0]); vi = vi - 1 if vi > 0 else len(V) + vi
            ti = int(s[1]) - 1 if len(s) > 1 and s[1] else -1
            c.append((vi, ti))
        for k in range(1, len(c) - 1): cur[1].append((c[0], c[k], c[k + 1]))
if cur[1]: objs.append(cur)
for _ in range(times):
    vm, tm = {}, {}
    def mid(a, b, L, M):
        key = (min(a, b), max(a, b))
        if key not in M:
            L.append(tuple((x + y) / 2 for x, y in zip(L[a], L[b]))); M[key] = len(L) - 1
        return M[key]
    for o in objs:
        out = []
        for (a, b, c) in o[1]:
            ab = (mid(a[0], b[0], V, vm), mid(a[1], b[1], VT, tm) if a[1] >= 0 else -1)
            bc = (mid(b[0], c[0], V, vm), mid(b[1], c[1], VT, tm) if b[1] >= 0 else -1)
            ca = (mid(c[0], a[0], V, vm), mid(c[1], a[1], VT, tm) if c[1] >= 0 else -1)
            out += [(a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)]
        o[1] = out
with open(dst, 'w') as f:
    for v in V: f.write('v %.7g %.7g %.7g\n' % v)
    for t in VT: f.write('vt %.7g %.7g\n' % t)
    for name, tris in objs:
        f.write(f'o {name}\n')
        for t in tris:
            f.write('f ' + ' '.join(f'{v+1}/{vt+1}' if vt >= 0 else f'{v+1}' for v, vt in t) + '\n')
print(sum(len(o[1]) for o in objs), 'triangles')
