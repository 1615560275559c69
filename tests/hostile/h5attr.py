"""Reads or overwrites a scalar numeric attribute of an HDF5 file in place, without h5py.

Usage: h5attr.py FILE NAME [NEW_VALUE]. Works on the version-1 attribute messages the project's
files use: the value keeps its stored type (an integer is wrapped to its width, so a huge value
becomes whatever the low bytes say; a float is stored as given: nan, inf, 1e308 ...).
"""
import struct
import sys


def pad8(n):
    return (n + 7) // 8 * 8


def locate(data, name):
    key = name.encode() + b"\0"
    start = 0
    while True:
        i = data.find(key, start)
        if i < 0:
            raise SystemExit(f"h5attr: no attribute {name}")
        if i >= 8 and data[i - 8] == 1:
            name_size, dt_size, ds_size = struct.unpack_from("<HHH", data, i - 6)
            if name_size == len(key):
                dt = i + pad8(name_size)
                cls = data[dt] & 0x0F
                size = struct.unpack_from("<I", data, dt + 4)[0]
                signed = bool(data[dt + 1] & 0x08)
                value_at = dt + pad8(dt_size) + pad8(ds_size)
                return cls, size, signed, value_at
        start = i + 1


def main():
    path, name = sys.argv[1], sys.argv[2]
    data = bytearray(open(path, "rb").read())
    cls, size, signed, at = locate(data, name)
    if cls == 1:
        fmt = "<d" if size == 8 else "<f"
    elif cls == 0:
        fmt = {1: "b", 2: "h", 4: "i", 8: "q"}[size]
        fmt = "<" + (fmt if signed else fmt.upper())
    else:
        raise SystemExit(f"h5attr: {name} is not a number (class {cls})")
    if len(sys.argv) == 3:
        print(struct.unpack_from(fmt, data, at)[0])
        return
    text = sys.argv[3]
    if cls == 1:
        value = float(text)
    else:
        value = int(float(text)) if "e" in text.lower() else int(text)
        bits = size * 8
        value &= (1 << bits) - 1
        if signed and value >= 1 << (bits - 1):
            value -= 1 << bits
    struct.pack_into(fmt, data, at, value)
    open(path, "wb").write(data)


main()
