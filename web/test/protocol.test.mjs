// The viewer's protocol v1 codec (src/protocol.js) against the byte layout of
// docs/protocol.md: 156-byte "LWF1" frames, "LWP1" poses, joint lookup by name.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { outputSkeleton } from '../src/session.js';
import { frameBinary, decodeFrameBinary, encodePoseBinary, decodePoseBinary, frameJSON, helloMessage, findJoint } from '../src/protocol.js';

const frame = { t: 12.345678901, head: { p: [0.1, 1.6, -0.2], q: [1, 0, 0, 0] }, right: { p: [-0.3, 1.0, 0.25], q: [0.5, 0.5, 0.5, 0.5] }, left_foot: { p: [0.1, 0.08, 0] } };

test('binary frame: 156 bytes, magic, float64 time, device mask, float32 poses', () => {
  const buf = frameBinary(frame);
  assert.equal(buf.byteLength, 156);
  const v = new DataView(buf);
  assert.equal(String.fromCharCode(...new Uint8Array(buf, 0, 4)), 'LWF1');
  assert.equal(v.getFloat64(4, true), frame.t);
  assert.equal(v.getUint8(12), 0b01101); // head, right hand, left foot
  assert.deepEqual([...new Uint8Array(buf, 13, 3)], [0, 0, 0]);
  // right hand = device 2: px at 16 + 2*28
  assert.ok(Math.abs(v.getFloat32(16 + 56, true) - -0.3) < 1e-7);
  assert.equal(v.getFloat32(16 + 56 + 12, true), 0.5); // qw
  const back = decodeFrameBinary(new Uint8Array(buf));
  assert.equal(back.t, frame.t);
  assert.equal(back.left, undefined);
  back.right.p.forEach((x, k) => assert.ok(Math.abs(x - frame.right.p[k]) < 1e-6));
});

test('binary pose round trip and truncated input', () => {
  const pose = { t: 3.5, seq: 41, status: 'degraded', rotations: [[1, 0, 0, 0], [0, 1, 0, 0]], positions: [[0, 1, 2], [3, 4, 5]] };
  const buf = encodePoseBinary(pose);
  assert.equal(buf.byteLength, 24 + 2 * 28);
  const p = decodePoseBinary(buf);
  assert.equal(p.t, 3.5);
  assert.equal(p.seq, 41);
  assert.equal(p.status, 'degraded');
  assert.deepEqual(p.positions, pose.positions);
  assert.deepEqual(p.rotations, pose.rotations);
  assert.equal(decodePoseBinary(buf.slice(0, 60)), null);
  assert.equal(decodePoseBinary(new ArrayBuffer(8)), null);
});

test('JSON frame and hello leave out untracked devices and unset options', () => {
  const m = JSON.parse(frameJSON(frame));
  assert.deepEqual(Object.keys(m).sort(), ['head', 'left_foot', 'right', 't', 'type']);
  assert.deepEqual(m.left_foot, { p: [0.1, 0.08, 0] });
  assert.deepEqual(helloMessage({ method: 'ik', classes: undefined }), { type: 'hello', version: 1, method: 'ik' });
});

test('hand and head joints are found in CMU, Mixamo and Unity names', () => {
  const cmu = ['Hips', 'LHipJoint', 'LeftUpLeg', 'Neck1', 'Head', 'LeftShoulder', 'LeftArm', 'LeftForeArm', 'LeftHand', 'LeftFingerBase', 'RightHand'];
  assert.equal(findJoint(cmu, 'left_hand'), 8);
  assert.equal(findJoint(cmu, 'right_hand'), 10);
  assert.equal(findJoint(cmu, 'head'), 4);
  assert.equal(findJoint(['mixamorig:Hips', 'mixamorig:LeftHand'], 'left_hand'), 1);
  assert.equal(findJoint(['hips', 'left_wrist'], 'left_hand'), 1);
  assert.equal(findJoint(['Hips'], 'right_hand'), -1);
});

test('a joint subset in welcome.joints becomes the skeleton of the poses', () => {
  const skeleton = { names: ['Hips', 'Spine', 'Neck', 'Head', 'LeftArm', 'LeftHand'], parents: [-1, 0, 1, 2, 1, 4] };
  assert.equal(outputSkeleton({ skeleton, joints: skeleton.names }), skeleton);
  assert.equal(outputSkeleton({ skeleton }), skeleton);
  assert.deepEqual(outputSkeleton({ skeleton, joints: ['Hips', 'Head', 'LeftHand'] }), { names: ['Hips', 'Head', 'LeftHand'], parents: [-1, 0, 0] });
});
