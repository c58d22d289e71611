// The three.js stage: renderer, lights, floor + grid, orbit camera, and HTML
// labels pinned to 3D points (crisp text at any resolution, also in screenshots).
import * as THREE from 'three';
import { material, quality as QUALITY } from './materials.js';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';

export class Stage {
  // quality: 'high' (antialias, soft shadows) or 'low' (for software GL: no AA, no shadows).
  constructor(canvas, labelLayer, quality = 'high') {
    this.canvas = canvas;
    this.labelLayer = labelLayer;
    this.quality = quality;
    const high = quality === 'high';
    QUALITY.low = !high;
    const r = (this.renderer = new THREE.WebGLRenderer({ canvas, antialias: high, preserveDrawingBuffer: true }));
    r.setPixelRatio(high ? Math.min(window.devicePixelRatio || 1, 2) : 1);
    r.shadowMap.enabled = high;
    r.shadowMap.type = THREE.PCFShadowMap;
    r.toneMapping = THREE.ACESFilmicToneMapping;
    r.toneMappingExposure = 1.05;
    r.outputColorSpace = THREE.SRGBColorSpace;

    const s = (this.scene = new THREE.Scene());
    s.background = new THREE.Color(0x1a2029);
    s.fog = new THREE.Fog(0x1a2029, 9, 22);

    this.camera = new THREE.PerspectiveCamera(38, 1, 0.05, 100);
    this.camera.position.set(0.6, 1.75, 5.6);
    this.controls = new OrbitControls(this.camera, canvas);
    this.controls.target.set(0, 0.95, 0);
    this.controls.enableDamping = true;
    this.controls.maxPolarAngle = Math.PI * 0.495;

    s.add(new THREE.HemisphereLight(0xdde8ff, 0x3a3128, 1.3));
    const key = new THREE.DirectionalLight(0xfff1e0, 2.4);
    key.position.set(3, 6, 4);
    key.castShadow = true;
    key.shadow.mapSize.set(1024, 1024);
    Object.assign(key.shadow.camera, { left: -5, right: 5, top: 5, bottom: -5, near: 0.5, far: 20 });
    key.shadow.bias = -0.0005;
    key.shadow.radius = 4;
    s.add(key);
    const rim = new THREE.DirectionalLight(0x9fc4ff, 1.1);
    rim.position.set(-4, 3, -5);
    s.add(rim);

    // Floor with a 1 m grid (0.5 m fine lines) painted into a texture: mip-mapped lines
    // look the same on every GPU (GL line primitives vanish on some software renderers).
    const c = document.createElement('canvas');
    c.width = c.height = 256;
    const g = c.getContext('2d');
    g.fillStyle = '#262d37';
    g.fillRect(0, 0, 256, 256);
    g.fillStyle = '#323b48';
    g.fillRect(127, 0, 2, 256);
    g.fillRect(0, 127, 256, 2);
    g.fillStyle = '#46536a';
    g.fillRect(0, 0, 256, 3);
    g.fillRect(0, 0, 3, 256);
    const tex = new THREE.CanvasTexture(c);
    tex.wrapS = tex.wrapT = THREE.RepeatWrapping;
    tex.repeat.set(60, 60);
    tex.anisotropy = r.capabilities.getMaxAnisotropy();
    tex.colorSpace = THREE.SRGBColorSpace;
    const floor = new THREE.Mesh(new THREE.PlaneGeometry(60, 60), material({ map: tex, roughness: 0.95 }));
    floor.rotation.x = -Math.PI / 2;
    floor.receiveShadow = true;
    this.grid = new THREE.Group();
    this.grid.add(floor);
    s.add(this.grid);

    this.labels = [];
    this._v = new THREE.Vector3();
    window.addEventListener('resize', () => this.resize());
    this.resize();
  }

  resize() {
    const w = this.canvas.clientWidth || window.innerWidth, h = this.canvas.clientHeight || window.innerHeight;
    this.renderer.setSize(w, h, false);
    this.camera.aspect = w / h;
    // Centre the view in the part of the canvas the side panel leaves free.
    const panel = document.getElementById('panel');
    const left = panel && !panel.hidden && w > 700 ? panel.offsetLeft + panel.offsetWidth : 0;
    if (left) this.camera.setViewOffset(w, h, -left / 2, 0, w, h);
    else this.camera.clearViewOffset();
    this.camera.updateProjectionMatrix();
  }

  // A label: returns {el, title, stats, at: Vector3, visible}.
  addLabel(text, color) {
    const el = document.createElement('div');
    el.className = 'label';
    el.innerHTML = `<div class="title"></div><div class="stats"></div>`;
    el.querySelector('.title').textContent = text;
    el.style.color = color;
    this.labelLayer.appendChild(el);
    const label = { el, title: el.querySelector('.title'), stats: el.querySelector('.stats'), at: new THREE.Vector3(), visible: true };
    this.labels.push(label);
    return label;
  }

  // Grid scrolls with the anchor (follow mode): world metres modulo the 1 m cell.
  setGridOffset(dx, dz, yaw) {
    this.grid.rotation.y = yaw;
    const c = Math.cos(yaw), s = Math.sin(yaw);
    const x = -(dx - Math.round(dx)), z = -(dz - Math.round(dz));
    this.grid.position.set(c * x + s * z, 0, -s * x + c * z);
  }

  render() {
    this.controls.update();
    this.renderer.render(this.scene, this.camera);
    const w = this.canvas.clientWidth, h = this.canvas.clientHeight;
    for (const l of this.labels) {
      const v = this._v.copy(l.at).project(this.camera);
      const show = l.visible && v.z < 1;
      l.el.style.display = show ? '' : 'none';
      if (show) l.el.style.left = `${((v.x + 1) / 2) * w}px`, l.el.style.top = `${((1 - v.y) / 2) * h}px`;
    }
  }
}
