#!/usr/bin/env python3
"""Writes the three shipped walks (data/walks/*.json) for the CMU skeleton.

The walks are authored here as anatomical angles (hip/knee/ankle/toe flexion,
shoulder swing and elbow bend, pelvis and spine) and written as the joint-local
Euler angles the walk format stores (degrees, [x, y, z], R = Rz*Ry*Rx). The
JSON files are the product; edit them directly or re-run this script.

CMU rest pose: every joint frame is aligned with the world (y up, character
faces +z, +x is the character's left). Leg bones splay 20 degrees outwards
and arms point sideways (T-pose), so each leg joint's flexion is a rotation
about the world x axis conjugated by the 20 degree splay correction, and each
arm is lowered first, then swung about x.
Sign conventions used below (left side; the right side is the mirror):
  leg (thigh, knee, ankle, toe): positive = the segment's far end moves back
      (thigh extension, knee flexion, ankle plantar flexion = toes down,
      toe curl down); negative thigh = forward.
  arm swing: positive = forward; elbow: positive = bends forward.
"""
import json, math, os, re, sys

SPLAY = 20.0  # degrees the CMU rest legs point outwards
ARM_DOWN = 75.0  # arms lowered from the T-pose


def q_axis(axis, deg):
    a = math.radians(deg) / 2
    s = math.sin(a)
    return (math.cos(a), s if axis == 'x' else 0.0, s if axis == 'y' else 0.0, s if axis == 'z' else 0.0)


def q_mul(a, b):
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return (aw * bw - ax * bx - ay * by - az * bz,
            aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw)


def q_chain(*qs):
    r = (1.0, 0.0, 0.0, 0.0)
    for q in qs:
        r = q_mul(r, q)
    return r


def euler_zyx(q):
    """[x, y, z] degrees with R = Rz(z) * Ry(y) * Rx(x)."""
    w, x, y, z = q
    r00 = 1 - 2 * (y * y + z * z)
    r10 = 2 * (x * y + w * z)
    r20 = 2 * (x * z - w * y)
    r21 = 2 * (y * z + w * x)
    r22 = 1 - 2 * (x * x + y * y)
    ry = math.asin(max(-1.0, min(1.0, -r20)))
    rz = math.atan2(r10, r00)
    rx = math.atan2(r21, r22)
    return [round(math.degrees(v), 3) + 0.0 for v in (rx, ry, rz)]


def conj_splay(s, axis_deg):
    """Flexion about world x for a leg joint whose rest bone splays outwards."""
    return q_chain(q_axis('z', SPLAY * s), q_axis('x', axis_deg), q_axis('z', -SPLAY * s))


def leg(side, thigh, knee, ankle, toe, abduct=0.0):
    s = 1 if side == 'Left' else -1
    j = {}
    j[side + 'UpLeg'] = q_chain(q_axis('x', thigh), q_axis('z', abduct * s), q_axis('z', -SPLAY * s))
    j[side + 'Leg'] = conj_splay(s, knee)
    j[side + 'Foot'] = conj_splay(s, ankle)
    j[side + 'ToeBase'] = conj_splay(s, toe)
    return j


def arm(side, swing, elbow, out=0.0):
    s = 1 if side == 'Left' else -1
    down = ARM_DOWN - out
    return {
        side + 'Arm': q_chain(q_axis('x', -swing), q_axis('z', -down * s)),
        side + 'ForeArm': q_chain(q_axis('z', down * s), q_axis('x', -elbow), q_axis('z', -down * s)),
    }


def euler_joint(x=0.0, y=0.0, z=0.0):
    return q_chain(q_axis('z', z), q_axis('y', y), q_axis('x', x))


def pose(L, R, LA, RA, hips=(5, 0, 0), lowerback=(-4, 0, 0), spine1=(2, 0, 0), neck=(-23, 0, 0),
         neck1=(25, 0, 0), head=(12, 0, 0), height='floor', wrists=(0, 0)):
    j = {}
    j.update(leg('Left', *L))
    j.update(leg('Right', *R))
    j.update(arm('Left', *LA))
    j.update(arm('Right', *RA))
    j['Hips'] = euler_joint(*hips)
    j['LowerBack'] = euler_joint(*lowerback)
    j['Spine1'] = euler_joint(*spine1)
    j['Neck'] = euler_joint(*neck)
    j['Neck1'] = euler_joint(*neck1)
    j['Head'] = euler_joint(*head)
    j['LeftHand'] = euler_joint(0, 0, -wrists[0])
    j['RightHand'] = euler_joint(0, 0, wrists[1])
    out = {'root': {'height': height}, 'rotations': {}}
    for name, q in j.items():
        e = euler_zyx(q)
        if max(abs(v) for v in e) >= 0.0005:
            out['rotations'][name] = e
    return out


def stand(**kw):
    p = pose(L=(0, 0, 0, 0), R=(0, 0, 0, 0), LA=(0, 8), RA=(0, 8), **kw)
    del p['root']
    return p


WALKS = {}

# Normal walk: Williams' four poses. Heights come from the legs ("floor").
WALKS['normal'] = {
    'description': 'A plain walk on 12s: heel strike at contact, lowest at down, legs crossing at pass, '
                   'highest at up on the ball of the stance foot; arms swing opposite the legs with the '
                   'elbows shifted one frame behind the shoulders.',
    'frames_per_cycle': 24, 'fps': 24,
    'keys': {
        'contact': pose(L=(-25, 4, -8, 0), R=(18, 10, 5, -34), LA=(-20, 10), RA=(22, 25),
                        hips=(5, -6, 0), spine1=(2, 6, 0)),
        'down': pose(L=(-20, 32, -13, 0), R=(12, 48, 0, -10), LA=(-26, 12), RA=(26, 30),
                     hips=(6, -4, -2), spine1=(3, 4, 1)),
        'pass': pose(L=(-2, 8, -6, 0), R=(-18, 62, -8, 0), LA=(0, 15), RA=(2, 18),
                     hips=(5, 0, -3), spine1=(2, 0, 2)),
        'up': pose(L=(14, 4, 12, -22), R=(-32, 30, -10, 0), LA=(16, 20), RA=(-14, 12),
                   hips=(5, 4, -1), spine1=(2, -4, 1)),
    },
    'shift': {'LeftArm': 1, 'LeftForeArm': 2, 'LeftHand': 3},
    'stand': stand(),
}

# Sneak: crouched, leaning forward, long slow reaching steps, hands up in front.
# (Arm swing is measured in the torso's frame, which leans forward ~40 degrees
# here, so the arms need large swing angles to come up in front.)
WALKS['sneak'] = {
    'description': 'A cartoon sneak: crouched and leaning forward, long slow reaching steps landing heel '
                   'first with the toes up, the body lowest just after contact and rising onto the ball of '
                   'the stance foot at up; hands held up in front with bent wrists, head pushed forward. '
                   'Slower (32 frames per cycle) and the down pose held longer.',
    'frames_per_cycle': 32, 'fps': 24,
    'timing': {'down': 5, 'pass': 9, 'up': 12},
    'keys': {
        'contact': pose(L=(-45, 25, -5, 0), R=(10, 30, 10, -30), LA=(75, 90, 0), RA=(90, 85, 0),
                        hips=(8, -8, 0), lowerback=(18, 0, 0), spine1=(14, 8, 0), neck=(-30, 0, 0),
                        head=(-5, 0, 0), wrists=(50, 50)),
        'down': pose(L=(-35, 60, -15, 0), R=(0, 75, 10, -20), LA=(70, 95, 0), RA=(95, 90, 0),
                     hips=(10, -5, -2), lowerback=(20, 0, 0), spine1=(16, 5, 1), neck=(-34, 0, 0),
                     head=(-8, 0, 0), wrists=(55, 55)),
        'pass': pose(L=(-18, 45, -14, 0), R=(-55, 110, -5, 0), LA=(80, 90, 0), RA=(85, 90, 0),
                     hips=(9, 0, -3), lowerback=(19, 0, 0), spine1=(15, 0, 2), neck=(-32, 0, 0),
                     head=(-6, 0, 0), wrists=(50, 50)),
        'up': pose(L=(5, 35, 25, -30), R=(-70, 75, 0, 0), LA=(90, 85, 0), RA=(75, 95, 0),
                   hips=(8, 6, -1), lowerback=(18, 0, 0), spine1=(14, -6, 1), neck=(-30, 0, 0),
                   head=(-4, 0, 0), wrists=(50, 50)),
    },
    'shift': {'LeftArm': 1, 'LeftForeArm': 2, 'Head': 1},
    'stand': stand(hips=(6, 0, 0), lowerback=(10, 0, 0), spine1=(8, 0, 0)),
}

# Double bounce: the body rises and dips twice per step (high at contact and
# pass, low at down and up), springy knees, bouncing arms.
WALKS['double-bounce'] = {
    'description': 'A double-bounce walk: the pelvis goes up and down twice per step - high at contact and '
                   'on tiptoe at pass, dipping with bent knees at down and again at up - with springy arms '
                   'and a head that bobs a frame late. Same 24-frame cycle as the normal walk.',
    'frames_per_cycle': 24, 'fps': 24,
    'keys': {
        'contact': pose(L=(-22, 0, 8, 0), R=(18, 5, 15, -30), LA=(-18, 30), RA=(22, 45),
                        hips=(3, -5, 0), spine1=(0, 5, 0), head=(10, 0, 0)),
        'down': pose(L=(-30, 50, -12, 0), R=(10, 55, 10, -10), LA=(-10, 55), RA=(30, 70),
                     hips=(6, -3, -2), spine1=(4, 3, 0), head=(18, 0, 0)),
        'pass': pose(L=(-4, 0, 25, -25), R=(-30, 80, 10, 0), LA=(5, 35), RA=(10, 40),
                     hips=(3, 0, -3), spine1=(0, 0, 2), head=(8, 0, 0)),
        'up': pose(L=(0, 45, -10, 0), R=(-42, 62, -15, 0), LA=(20, 60), RA=(-5, 50),
                   hips=(6, 3, -2), spine1=(4, -3, 1), head=(18, 0, 0)),
    },
    'shift': {'Head': 1, 'Neck1': 1, 'LeftForeArm': 1},
    'stand': stand(),
}


def main():
    out_dir = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), '..', 'data', 'walks')
    os.makedirs(out_dir, exist_ok=True)
    for name, w in WALKS.items():
        doc = {'format': 'legwork-walk/1', 'name': name, 'description': w['description'],
               'skeleton': '../cmu/bvh/walking/07_01.bvh', 'frames_per_cycle': w['frames_per_cycle'],
               'fps': w['fps'], 'euler_order': 'ZYX'}
        if 'timing' in w:
            doc['timing'] = w['timing']
        doc['keys'] = w['keys']
        if 'inbetweens' in w:
            doc['inbetweens'] = w['inbetweens']
        doc['shift'] = w['shift']
        doc['stand'] = w['stand']
        path = os.path.join(out_dir, name + '.json')
        text = json.dumps(doc, indent=2)
        # One line per [x, y, z] triple.
        text = re.sub(r'\[\s*(-?[\d.e+-]+),\s*(-?[\d.e+-]+),\s*(-?[\d.e+-]+)\s*\]', r'[\1, \2, \3]', text)
        text = re.sub(r'\{\s*"frame": ([\d.]+),\s*"root": \{\s*"height": "floor"\s*\}\s*\}', r'{"frame": \1, "root": {"height": "floor"}}', text)
        with open(path, 'w') as f:
            f.write(text + '\n')
        print('wrote', path)


if __name__ == '__main__':
    main()
