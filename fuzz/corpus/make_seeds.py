#!/usr/bin/env python3
"""Writes the seed corpora of the protocol, VMC and path fuzz targets
(fuzz/corpus/{protocol,vmc,path}/): a standing user's head and controllers
(metres, quaternions w, x, y, z), every message type and SVG command once.
The files are committed; this script documents (and can remake) them."""
import json
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
HEAD = ([0.151, 1.618, 0.912], [0.996, 0.012, 0.087, -0.004])   # p, q (w, x, y, z)
LEFT = ([0.352, 0.878, 0.871], [0.701, 0.112, 0.693, 0.121])
RIGHT = ([-0.088, 0.861, 1.005], [0.683, -0.101, 0.717, -0.095])


def write(folder, name, data):
    os.makedirs(os.path.join(HERE, folder), exist_ok=True)
    with open(os.path.join(HERE, folder, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


def protocol():
    dev = lambda d: {"p": d[0], "q": d[1]}
    write("protocol", "hello.json", json.dumps({"type": "hello", "version": 1, "method": "ik", "format": "binary",
                                                "joints": ["Hips", "Head", "LeftHand"], "user_height": 1.7,
                                                "classes": ["walking"], "exaggeration": 1.2, "record": False}))
    write("protocol", "frame.json", json.dumps({"type": "frame", "t": 0.4444, "head": dev(HEAD), "left": dev(LEFT),
                                                "right": dev(RIGHT), "left_foot": None}))
    write("protocol", "options.json", json.dumps({"type": "options", "exaggeration": 1.5, "classes": None}))
    frame = b"LWF1" + struct.pack("<dB3x", 0.4444, 0b111)
    for p, q in (HEAD, LEFT, RIGHT, ([0, 0, 0], [1, 0, 0, 0]), ([0, 0, 0], [1, 0, 0, 0])):
        frame += struct.pack("<7f", *p, *q)
    assert len(frame) == 156
    write("protocol", "frame.bin", frame)


def osc_string(s):
    b = s.encode() + b"\0"
    return b + b"\0" * (-len(b) % 4)


def osc_device(path, serial, p, q, double=False):
    # VMC: serial, position xyz, quaternion xyzw, in Unity's frame (x mirrored).
    values = [-p[0], p[1], p[2], q[1], -q[2], -q[3], q[0]]
    tags = "," + "s" + ("d" if double else "f") * 7
    return osc_string(path) + osc_string(tags) + osc_string(serial) + struct.pack(">7" + ("d" if double else "f"), *values)


def framed(*packets):
    return b"".join(struct.pack(">i", len(p)) + p for p in packets)


def vmc():
    hmd = osc_device("/VMC/Ext/Hmd/Pos", "HMD", *HEAD)
    left = osc_device("/VMC/Ext/Con/Pos", "LHR-LEFT", *LEFT)
    right = osc_device("/VMC/Ext/Con/Pos", "LHR-RIGHT", *RIGHT, double=True)
    tracker = osc_device("/VMC/Ext/Tra/Pos", "LHR-FOOT", [0.1, 0.08, 0.9], [1, 0, 0, 0])
    write("vmc", "messages.bin", framed(hmd, left, right, tracker))
    bundle = osc_string("#bundle") + struct.pack(">Q", 1)
    for m in (hmd, left, right):
        bundle += struct.pack(">i", len(m)) + m
    write("vmc", "bundle.bin", framed(bundle, tracker))


def paths():
    write("path", "polyline.json", json.dumps({"polyline": [[0, 0], [0, 2], [1, 3], [3, 3]]}))
    write("path", "catmull_rom.json", json.dumps({"catmull_rom": [[0, 0], [0, 2], [2, 4], [2, 6]], "samples_per_segment": 8}))
    write("path", "svg_all.json", json.dumps({"svg": "M 0 0 L 0 1 H 1 V 2 C 1 3 2 3 2 4 S 3 5 3 6 Q 4 7 5 7 l 1 0 h 1 v 1 "
                                                      "c 0 1 1 1 1 2 s 1 1 1 2 q 1 1 2 1 z"}))


if __name__ == "__main__":
    protocol()
    vmc()
    paths()
