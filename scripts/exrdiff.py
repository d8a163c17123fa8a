#!/usr/bin/env python3
# scripts/exrdiff.py A.exr B.exr [LABEL]: one line with the mean and max |A - B| over every channel of two
# scanline EXR files (ZIP, ZIPS or no compression; HALF or FLOAT samples), and how many values differ by
# more than 2e-3. Plain Python (no numpy or OpenEXR module), so that it runs on a GPU machine as it is:
# scripts/gpu-verify uses it to set `render --gpu` against the CPU. Exit 1 with one line for a file that
# is not such an EXR or two files of different channels or sizes.
import array, itertools, struct, sys, zlib

def read_exr(path):
    data = open(path, 'rb').read()
    assert struct.unpack_from('<I', data, 0)[0] == 20000630, path + ': not EXR'
    pos, attrs = 8, {}
    while data[pos] != 0:
        end = data.index(b'\0', pos); name = data[pos:end].decode(); pos = end + 1
        end = data.index(b'\0', pos); typ = data[pos:end].decode(); pos = end + 1
        size = struct.unpack_from('<i', data, pos)[0]; pos += 4
        attrs[name] = data[pos:pos + size]; pos += size
    pos += 1
    chans, raw, p = [], attrs['channels'], 0
    while raw[p] != 0:
        end = raw.index(b'\0', p); name = raw[p:end].decode(); p = end + 1
        chans.append((name, struct.unpack_from('<i', raw, p)[0])); p += 16
    xmin, ymin, xmax, ymax = struct.unpack('<iiii', attrs['dataWindow'])
    w, h = xmax - xmin + 1, ymax - ymin + 1
    comp = attrs['compression'][0]
    lines = {0: 1, 2: 1, 3: 16}[comp]
    offsets = struct.unpack_from('<%dQ' % ((h + lines - 1) // lines), data, pos)
    values = {name: array.array('f') for name, _ in chans}
    for off in offsets:
        y, size = struct.unpack_from('<ii', data, off)
        block = data[off + 8: off + 8 + size]
        n = min(lines, ymax + 1 - y)
        expected = sum(w * (2 if t == 1 else 4) for _, t in chans) * n
        if comp != 0 and size < expected:
            d = zlib.decompress(block)
            t = bytearray(itertools.accumulate(d, lambda a, b: (a + b - 128) & 0xFF))
            block = bytearray(len(t))
            half = (len(t) + 1) // 2
            block[0::2] = t[:half]
            block[1::2] = t[half:]
        p = 0
        for row in range(n):
            for name, t in chans:
                nbytes = w * (2 if t == 1 else 4)
                chunk = bytes(block[p:p + nbytes]); p += nbytes
                if t == 1:  # HALF: array has no 16-bit float type, struct does
                    values[name].extend(struct.unpack('<%de' % w, chunk))
                else:  # FLOAT (UINT read as its bits' float is still exact for equality)
                    a = array.array('f'); a.frombytes(chunk); values[name].extend(a)
    return values

def difference(a, b):
    """The sum and max of |A - B| over every value of two files read_exr read, the count of values, and how
    many differ by more than 2e-3. ValueError if their channels or sizes differ."""
    if sorted(a) != sorted(b) or any(len(a[n]) != len(b[n]) for n in a):
        raise ValueError('differ in channels or size')
    total, worst, count, over = 0.0, 0.0, 0, 0
    for name in a:
        for x, y in zip(a[name], b[name]):
            # Equal infinities (sky depths) and two NaNs count as equal; one NaN against a number as infinite.
            d = 0.0 if x == y or (x != x and y != y) else abs(x - y) if x == x and y == y else float('inf')
            total += d; worst = max(worst, d); count += 1; over += d > 2e-3
    return total, worst, count, over

def main():
    if len(sys.argv) not in (3, 4):
        sys.exit('usage: exrdiff.py A.exr B.exr [LABEL]')
    try:
        a, b = read_exr(sys.argv[1]), read_exr(sys.argv[2])
    except (OSError, AssertionError, KeyError, IndexError, struct.error, zlib.error) as e:
        sys.exit('exrdiff.py: %s: not a scanline EXR this script reads (%s)' % (' or '.join(sys.argv[1:3]), e))
    try:
        total, worst, count, over = difference(a, b)
    except ValueError as e:
        sys.exit('exrdiff.py: %s and %s %s' % (sys.argv[1], sys.argv[2], e))
    label = sys.argv[3] if len(sys.argv) == 4 else sys.argv[2]
    print('%-100s mean |diff| %.2e  max %.2e  values > 2e-3: %d of %d' % (label, total / max(count, 1), worst, over, count))

if __name__ == '__main__':
    main()
