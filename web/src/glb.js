// Walk-cycle playback of a GLB (e.g. `legwork walkcycle ... --glb`): three's
// GLTFLoader + AnimationMixer drive the node hierarchy; the bones' world
// positions feed the same capsule body as the live avatars.
import * as THREE from 'three';
import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';
import { Body } from './avatar.js';

export class GLBPlayer {
  constructor(stage) {
    this.stage = stage;
    this.group = new THREE.Group();
    stage.scene.add(this.group);
    this.loader = new GLTFLoader();
    this.mixer = null;
    this.action = null;
    this.clip = null;
    this.nodes = [];
    this.body = null;
    this.label = stage.addLabel('Walk cycle', '#7ee2a8');
    this.label.at.set(0, 2.05, 0);
    this.label.visible = false;
    this.info = { loaded: false, name: '', duration: 0, joints: 0, time: 0 };
  }

  async loadURL(url) { return this._parse(await (await fetch(url)).arrayBuffer(), url); }
  async loadFile(file) { return this._parse(await file.arrayBuffer(), file.name); }

  _parse(buffer, name) {
    return new Promise((resolve, reject) => this.loader.parse(buffer, '', (gltf) => resolve(this._setup(gltf, name)), reject));
  }

  _setup(gltf, name) {
    this.group.clear();
    const root = gltf.scene;
    this.group.add(root);
    // Joints: the skin's bones if any, else every node with a name that is not a mesh.
    let nodes = [];
    root.traverse((o) => { if (o.isBone) nodes.push(o); });
    if (!nodes.length) root.traverse((o) => { if (o !== root && !o.isMesh && o.name) nodes.push(o); });
    root.traverse((o) => { if (o.isMesh) o.visible = false; });
    this.nodes = nodes;
    const parents = nodes.map((o) => nodes.indexOf(o.parent));
    this.body = new Body(0x7ee2a8);
    this.body.setSkeleton(nodes.map((o) => o.name), parents);
    this.group.add(this.body.group);
    this.mixer = new THREE.AnimationMixer(root);
    this.clip = gltf.animations[0] || null;
    this.action = this.clip ? this.mixer.clipAction(this.clip).play() : null;
    Object.assign(this.info, { loaded: true, name, duration: this.clip ? this.clip.duration : 0, joints: nodes.length, time: 0, clip: this.clip?.name || '' });
    this.label.title.textContent = `Walk cycle · ${name.split('/').pop()}`;
    this.update(0);
    return this.info;
  }

  seek(t) { if (this.mixer) { this.mixer.setTime(t); this.update(0); } }

  update(dt) {
    if (!this.mixer) return;
    this.mixer.update(dt);
    this.group.updateMatrixWorld(true);
    const v = new THREE.Vector3();
    const pts = this.nodes.map((o) => o.getWorldPosition(v).toArray());
    const [rx, , rz] = pts[0] || [0, 0, 0]; // keep a walking root in view: follow it horizontally
    for (const p of pts) { p[0] -= rx; p[2] -= rz; }
    this.stage.setGridOffset(rx, rz, 0);
    this.body.setPositions(pts);
    this.info.positions = pts;
    this.info.updates = (this.info.updates || 0) + 1;
    this.info.time = this.clip ? this.mixer.time % this.clip.duration : 0;
    this.label.stats.textContent = `${this.info.joints} joints · ${this.info.duration.toFixed(2)} s loop · t ${this.info.time.toFixed(2)} s`;
  }
}
