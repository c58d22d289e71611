// A small animated GLB written by hand (glTF 2.0 binary): a 15-joint body whose
// legs and arms swing over a 1 s loop, for testing the viewer's walk-cycle mode
// without the C++ CLI. `legwork walkcycle ... --glb` files are the real input.
const JOINTS = [
  ['Hips', -1, [0, 0.95, 0]], ['Spine', 0, [0, 0.25, 0]], ['Neck', 1, [0, 0.28, 0]], ['Head', 2, [0, 0.12, 0]],
  ['LeftArm', 1, [0.19, 0.24, 0]], ['LeftForeArm', 4, [0, -0.28, 0]], ['LeftHand', 5, [0, -0.26, 0]],
  ['RightArm', 1, [-0.19, 0.24, 0]], ['RightForeArm', 7, [0, -0.28, 0]], ['RightHand', 8, [0, -0.26, 0]],
  ['LeftUpLeg', 0, [0.1, -0.06, 0]], ['LeftLeg', 10, [0, -0.42, 0]], ['LeftFoot', 11, [0, -0.41, 0]],
  ['RightUpLeg', 0, [-0.1, -0.06, 0]], ['RightLeg', 13, [0, -0.42, 0]], ['RightFoot', 14, [0, -0.41, 0]],
];
const SWING = { LeftUpLeg: 0.45, RightUpLeg: -0.45, LeftArm: -0.35, RightArm: 0.35, LeftLeg: 0.3, RightLeg: 0.3 };

export function walkGLB(keys = 17, period = 1) {
  const times = Array.from({ length: keys }, (_, k) => (k / (keys - 1)) * period);
  const floats = [...times];
  const accessors = [{ bufferView: 0, byteOffset: 0, componentType: 5126, count: keys, type: 'SCALAR', min: [0], max: [period] }];
  const channels = [], samplers = [];
  JOINTS.forEach(([name], node) => {
    if (!(name in SWING)) return;
    const offset = floats.length * 4;
    for (const t of times) {
      const phase = Math.sin((2 * Math.PI * t) / period);
      const a = (name.endsWith('Leg') && !name.includes('Up') ? Math.max(0, phase) : phase) * SWING[name];
      floats.push(Math.sin(a / 2), 0, 0, Math.cos(a / 2)); // about x, glTF order x y z w
    }
    accessors.push({ bufferView: 0, byteOffset: offset, componentType: 5126, count: keys, type: 'VEC4' });
    samplers.push({ input: 0, output: accessors.length - 1, interpolation: 'LINEAR' });
    channels.push({ sampler: samplers.length - 1, target: { node, path: 'rotation' } });
  });
  // root moves forward 1.2 m per loop
  const offset = floats.length * 4;
  for (const t of times) floats.push(0, 0.95, (1.2 * t) / period);
  accessors.push({ bufferView: 0, byteOffset: offset, componentType: 5126, count: keys, type: 'VEC3' });
  samplers.push({ input: 0, output: accessors.length - 1, interpolation: 'LINEAR' });
  channels.push({ sampler: samplers.length - 1, target: { node: 0, path: 'translation' } });

  const bin = Buffer.from(new Float32Array(floats).buffer);
  const nodes = JOINTS.map(([name, , t]) => ({ name, translation: t }));
  JOINTS.forEach(([, parent], j) => { if (parent >= 0) (nodes[parent].children ||= []).push(j); });
  const gltf = { asset: { version: '2.0', generator: 'legwork viewer test fixture' }, scene: 0, scenes: [{ nodes: [0] }], nodes,
    buffers: [{ byteLength: bin.length }], bufferViews: [{ buffer: 0, byteOffset: 0, byteLength: bin.length }], accessors,
    animations: [{ name: 'walk', channels, samplers }] };
  let json = Buffer.from(JSON.stringify(gltf));
  json = Buffer.concat([json, Buffer.alloc((4 - (json.length % 4)) % 4, 0x20)]);
  const header = Buffer.alloc(12), jh = Buffer.alloc(8), bh = Buffer.alloc(8);
  header.writeUInt32LE(0x46546c67, 0); header.writeUInt32LE(2, 4); header.writeUInt32LE(12 + 8 + json.length + 8 + bin.length, 8);
  jh.writeUInt32LE(json.length, 0); jh.writeUInt32LE(0x4e4f534a, 4);
  bh.writeUInt32LE(bin.length, 0); bh.writeUInt32LE(0x004e4942, 4);
  return Buffer.concat([header, jh, json, bh, bin]);
}
