// A shaded body drawn from world joint positions: a sphere at each joint and a
// cylinder along each bone (together: capsules), radii chosen from the bone's
// name so any skeleton (CMU, the server's database, a GLB) looks like a body.
// Plus the tracked devices as markers: a headset box and two controllers.
import * as THREE from 'three';
import { material } from './materials.js';

const BONE_RADIUS = [
  [/hipjoint/, 0.06],
  [/spine|chest|hip|pelvis|torso|abdomen|lowerback/, 0.085],
  [/neck/, 0.045],
  [/upleg|thigh|upperleg/, 0.07],
  [/leg|shin|calf|knee/, 0.05],
  [/toe/, 0.03],
  [/foot|ankle/, 0.04],
  [/forearm|lowerarm|elbow/, 0.036],
  [/arm|shoulder|clavicle|collar/, 0.042],
  [/finger|thumb|index|middle|ring|pinky|hand|wrist/, 0.022],
];

function radiusFor(name) {
  const n = String(name).toLowerCase();
  for (const [re, r] of BONE_RADIUS) if (re.test(n)) return r;
  return 0.04;
}

const UP = new THREE.Vector3(0, 1, 0);
const cylGeo = new THREE.CylinderGeometry(1, 1, 1, 16, 1, true);
const sphereGeo = new THREE.SphereGeometry(1, 20, 14);

export class Body {
  constructor(color, { opacity = 1 } = {}) {
    this.group = new THREE.Group();
    this.material = material({ color, roughness: 0.55, metalness: 0.05, transparent: opacity < 1, opacity });
    this.names = [];
    this.parents = [];
    this.bones = [];
    this.joints = [];
    this.head = null;
    this.headIndex = -1;
    this._a = new THREE.Vector3();
    this._b = new THREE.Vector3();
  }

  setSkeleton(names, parents) {
    for (const m of [...this.bones, ...this.joints]) this.group.remove(m);
    if (this.head) this.group.remove(this.head);
    this.names = names;
    this.parents = parents;
    this.bones = [];
    this.joints = [];
    this.headIndex = names.findIndex((n) => /^head$/i.test(String(n).replace(/^mixamorig:/i, '')));
    const childRadius = names.map(() => 0);
    names.forEach((n, j) => {
      const p = parents[j];
      if (p < 0) return;
      const r = Math.min(radiusFor(n.match(/hand|wrist/i) ? n : names[p]), radiusFor(n) * 1.4);
      const bone = new THREE.Mesh(cylGeo, this.material);
      bone.castShadow = true;
      bone.userData = { from: p, to: j, r: radiusFor(names[p].match(/hips|pelvis/i) ? n : names[p]) };
      this.bones.push(bone);
      this.group.add(bone);
      childRadius[p] = Math.max(childRadius[p], bone.userData.r);
      childRadius[j] = Math.max(childRadius[j], Math.min(bone.userData.r, r));
    });
    names.forEach((n, j) => {
      const s = new THREE.Mesh(sphereGeo, this.material);
      s.castShadow = true;
      s.scale.setScalar(Math.max(childRadius[j], 0.02));
      this.joints.push(s);
      this.group.add(s);
    });
    this.head = new THREE.Mesh(sphereGeo, this.material);
    this.head.scale.set(0.095, 0.115, 0.1);
    this.head.castShadow = true;
    this.group.add(this.head);
    this.head.visible = this.headIndex >= 0;
    this.group.visible = false; // until the first pose
  }

  // positions: array of [x,y,z] per joint (display frame) or a flat array.
  setPositions(positions) {
    const at = Array.isArray(positions[0]) ? (j, v) => v.fromArray(positions[j]) : (j, v) => v.fromArray(positions, 3 * j);
    const a = this._a, b = this._b;
    this.group.visible = true;
    for (let j = 0; j < this.joints.length; ++j) at(j, this.joints[j].position);
    for (const bone of this.bones) {
      at(bone.userData.from, a);
      at(bone.userData.to, b);
      const d = b.clone().sub(a);
      const l = d.length();
      bone.visible = l > 1e-4;
      if (!bone.visible) continue;
      bone.position.copy(a).addScaledVector(d, 0.5);
      bone.quaternion.setFromUnitVectors(UP, d.multiplyScalar(1 / l));
      bone.scale.set(bone.userData.r, l, bone.userData.r);
    }
    if (this.headIndex >= 0) {
      const h = this.joints[this.headIndex].position;
      const p = this.parents[this.headIndex];
      const dir = p >= 0 ? h.clone().sub(this.joints[p].position).normalize() : UP.clone();
      this.head.position.copy(h).addScaledVector(dir, 0.09);
      this.head.quaternion.setFromUnitVectors(UP, dir);
    }
  }

  jointPosition(j, out = new THREE.Vector3()) {
    return out.copy(this.joints[j].position);
  }
}

// Headset and controllers at the tracked devices (display frame).
export class DeviceMarkers {
  constructor(color = 0x20252b) {
    this.group = new THREE.Group();
    const mat = material({ color, roughness: 0.35, metalness: 0.3 });
    const lens = material({ color: 0x66ccff, emissive: 0x1166aa, emissiveIntensity: 0.6 });
    this.headset = new THREE.Group();
    const shell = new THREE.Mesh(new THREE.BoxGeometry(0.19, 0.1, 0.1), mat);
    shell.position.set(0, 0.08, 0.1);
    const visor = new THREE.Mesh(new THREE.BoxGeometry(0.17, 0.07, 0.01), lens);
    visor.position.set(0, 0.08, 0.152);
    this.headset.add(shell, visor);
    this.controllers = ['left', 'right'].map((side) => {
      const g = new THREE.Group();
      const grip = new THREE.Mesh(new THREE.CylinderGeometry(0.018, 0.022, 0.12, 12), mat);
      const ring = new THREE.Mesh(new THREE.TorusGeometry(0.045, 0.008, 8, 24),
        material({ color: side === 'left' ? 0xff5a5f : 0x3ddc97, emissive: side === 'left' ? 0x551010 : 0x105533 }));
      ring.position.y = 0.07;
      g.add(grip, ring);
      return g;
    });
    this.group.add(this.headset, ...this.controllers);
    for (const o of [this.headset, ...this.controllers]) o.traverse((m) => { m.castShadow = true; });
  }

  // devices: {head:{p,q}, left:{p,q}, right:{p,q}} with q as [w,x,y,z]; missing = hidden.
  set(devices, offset) {
    const put = (obj, d) => {
      obj.visible = !!d;
      if (!d) return;
      obj.position.fromArray(d.p).add(offset);
      if (d.q) obj.quaternion.set(d.q[1], d.q[2], d.q[3], d.q[0]);
    };
    put(this.headset, devices.head);
    put(this.controllers[0], devices.left);
    put(this.controllers[1], devices.right);
  }
}
