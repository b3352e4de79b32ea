#!/usr/bin/env python3
"""Convert a Talus particles_*.0.vtu (deal.II, zlib-compressed binary) into the
CSV layout of run_case.py (x, y, volume, mass, vx, vy) so that measure.py measures
Talus and Kratos deposits with the same code. volume = initial_volume.
Usage: talus_vtu_to_csv.py IN.vtu OUT.csv"""
import base64, re, struct, sys, zlib, csv

def arrays(text):
    out = {}
    for m in re.finditer(r'<DataArray([^>]*)>\s*([^<]*)</DataArray>', text):
        attrs, data = m.group(1), m.group(2).strip()
        name = re.search(r'Name="([^"]+)"', attrs)
        name = name.group(1) if name else "Points"
        typ = re.search(r'type="([^"]+)"', attrs).group(1)
        ncomp = re.search(r'NumberOfComponents="(\d+)"', attrs)
        ncomp = int(ncomp.group(1)) if ncomp else 1
        hdr = base64.b64decode(data[:24])
        nb, bs, last, csz = struct.unpack('<4I', hdr)
        raw = zlib.decompress(base64.b64decode(data[24:]))
        fmt = {'Float32': 'f', 'Float64': 'd', 'Int32': 'i', 'UInt8': 'B'}[typ]
        vals = struct.unpack('<%d%s' % (len(raw) // struct.calcsize(fmt), fmt), raw)
        out[name] = [vals[i:i + ncomp] for i in range(0, len(vals), ncomp)]
    return out


def main():
    a = arrays(open(sys.argv[1]).read())
    with open(sys.argv[2], 'w', newline='') as f:
        w = csv.writer(f)
        w.writerow(["x", "y", "volume", "mass", "vx", "vy"])
        for p, v, m, vol in zip(a["Points"], a["velocity"], a["mass"], a["initial_volume"]):
            w.writerow([p[0], p[1], vol[0], m[0], v[0], v[1]])


if __name__ == "__main__":
    main()
