#!/usr/bin/env python3
"""Checks a VMC Performer stream as dumped by liblo-tools' oscdump (-L).

Usage: check_vmc.py DUMP LEFT_X,Y,Z RIGHT_X,Y,Z
Every bundle (one timetag) must hold /VMC/Ext/Root/Pos, one /VMC/Ext/Bone/Pos
per humanoid bone of legwork's CMU skeleton (the 21 names below, each once),
/VMC/Ext/OK 1 and /VMC/Ext/T; rotations are unit quaternions. The last
bundle's bones are chained from Hips (Unity frame: p = p_parent + R_parent p_local)
and the hands must lie within 1 cm of the given positions (Unity frame)."""
import math
import sys

BONES = ["Hips", "Spine", "Chest", "Neck", "Head",
         "LeftShoulder", "LeftUpperArm", "LeftLowerArm", "LeftHand",
         "RightShoulder", "RightUpperArm", "RightLowerArm", "RightHand",
         "LeftUpperLeg", "LeftLowerLeg", "LeftFoot", "LeftToes",
         "RightUpperLeg", "RightLowerLeg", "RightFoot", "RightToes"]
PARENT = {"Spine": "Hips", "Chest": "Spine", "Neck": "Chest", "Head": "Neck",
          "LeftShoulder": "Chest", "LeftUpperArm": "LeftShoulder", "LeftLowerArm": "LeftUpperArm",
          "LeftHand": "LeftLowerArm", "RightShoulder": "Chest", "RightUpperArm": "RightShoulder",
          "RightLowerArm": "RightUpperArm", "RightHand": "RightLowerArm",
          "LeftUpperLeg": "Hips", "LeftLowerLeg": "LeftUpperLeg", "LeftFoot": "LeftLowerLeg",
          "LeftToes": "LeftFoot", "RightUpperLeg": "Hips", "RightLowerLeg": "RightUpperLeg",
          "RightFoot": "RightLowerLeg", "RightToes": "RightFoot"}


def fail(msg):
    print("check_vmc: FAIL: " + msg)
    sys.exit(1)


def qmul(a, b):  # (x, y, z, w)
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (aw * bx + ax * bw + ay * bz - az * by, aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw, aw * bw - ax * bx - ay * by - az * bz)


def rotate(q, v):
    x, y, z, w = qmul(qmul(q, (v[0], v[1], v[2], 0.0)), (-q[0], -q[1], -q[2], q[3]))
    return (x, y, z)


def main():
    dump, left, right = sys.argv[1], [float(v) for v in sys.argv[2].split(",")], [float(v) for v in sys.argv[3].split(",")]
    bundles = {}
    order = []
    for line in open(dump):
        parts = line.split()
        if len(parts) < 3 or not parts[1].startswith("/VMC/Ext/"):
            continue
        tag = parts[0]
        if tag not in bundles:
            bundles[tag] = []
            order.append(tag)
        bundles[tag].append(parts[1:])
    if len(order) < 10:
        fail("only %d bundles received (expected a stream)" % len(order))
    for tag in order:
        msgs = bundles[tag]
        paths = [m[0] for m in msgs]
        if paths.count("/VMC/Ext/Root/Pos") != 1 or paths.count("/VMC/Ext/OK") != 1 or paths.count("/VMC/Ext/T") != 1:
            fail("bundle %s lacks Root/Pos, OK or T: %s" % (tag, sorted(set(paths))))
        names = [m[2].strip('"') for m in msgs if m[0] == "/VMC/Ext/Bone/Pos"]
        if sorted(names) != sorted(BONES):
            fail("bundle %s bones %s, expected %s" % (tag, names, BONES))
        for m in msgs:
            if m[0] in ("/VMC/Ext/Bone/Pos", "/VMC/Ext/Root/Pos"):
                if m[1] != "sfffffff":
                    fail("%s has types %s, expected sfffffff" % (m[0], m[1]))
                q = [float(v) for v in m[6:10]]
                if abs(math.sqrt(sum(c * c for c in q)) - 1) > 1e-3:
                    fail("%s %s rotation is not a unit quaternion: %s" % (m[0], m[2], q))
        if [m for m in msgs if m[0] == "/VMC/Ext/OK"][0][2] != "1":
            fail("/VMC/Ext/OK is not 1")
    last = {m[2].strip('"'): [float(v) for v in m[3:10]] for m in bundles[order[-1]] if m[0] == "/VMC/Ext/Bone/Pos"}
    world = {}
    for b in BONES:
        p, q = last[b][0:3], tuple(last[b][3:7])
        if b == "Hips":
            world[b] = (tuple(p), q)
        else:
            pp, pq = world[PARENT[b]]
            d = rotate(pq, p)
            world[b] = ((pp[0] + d[0], pp[1] + d[1], pp[2] + d[2]), qmul(pq, q))
    for name, want in (("LeftHand", left), ("RightHand", right)):
        got = world[name][0]
        err = math.dist(got, want)
        print("check_vmc: %s at (%.4f, %.4f, %.4f), input (%.4f, %.4f, %.4f): %.2f cm" % (name, *got, *want, err * 100))
        if err > 0.01:
            fail("%s is %.2f cm from the input (more than 1 cm)" % (name, err * 100))
    print("check_vmc: ok: %d bundles, %d bones each, names and values checked" % (len(order), len(BONES)))


main()
