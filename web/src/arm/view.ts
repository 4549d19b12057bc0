// The arm page's 3D view (three.js, z up): link capsules, the target, the
// tool path, the hand and forearm with their path, script and predicted
// positions, and the sampled step candidates. It only paints the arrays the
// wasm handle hands out; only the named three.js classes are imported so
// the bundle keeps what it uses.

import {
  AmbientLight,
  BufferGeometry,
  Color,
  CylinderGeometry,
  DirectionalLight,
  Float32BufferAttribute,
  GridHelper,
  Group,
  Line,
  LineBasicMaterial,
  LineDashedMaterial,
  Mesh,
  MeshStandardMaterial,
  PerspectiveCamera,
  Plane,
  Points,
  PointsMaterial,
  Quaternion,
  Raycaster,
  Scene,
  SphereGeometry,
  Vector2,
  Vector3,
  WebGLRenderer,
} from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

export interface Frame {
  links: Float32Array; // ax ay az bx by bz r per link
  hand: Float32Array; // sphere cx cy cz r, capsule ax ay az bx by bz r
  toolPath: Float32Array;
  handPath: Float32Array;
  predictions: Float32Array; // x y z range k
  candidates: Float32Array;
  chosen: number;
  goal: number[];
  start: number[];
}

const UP = new Vector3(0, 1, 0);

/** A capsule drawn as a unit cylinder and two spheres, re-posed per frame. */
class CapsuleMesh {
  readonly group = new Group();
  private readonly body: Mesh;
  private readonly capA: Mesh;
  private readonly capB: Mesh;
  constructor(cyl: CylinderGeometry, sph: SphereGeometry, mat: MeshStandardMaterial) {
    this.body = new Mesh(cyl, mat);
    this.capA = new Mesh(sph, mat);
    this.capB = new Mesh(sph, mat);
    this.group.add(this.body, this.capA, this.capB);
  }
  set(a: Vector3, b: Vector3, r: number): void {
    const d = new Vector3().subVectors(b, a);
    const len = d.length();
    this.capA.position.copy(a);
    this.capB.position.copy(b);
    this.capA.scale.setScalar(r);
    this.capB.scale.setScalar(r);
    this.body.visible = len > 1e-6;
    if (len > 1e-6) {
      this.body.position.addVectors(a, b).multiplyScalar(0.5);
      this.body.quaternion.copy(new Quaternion().setFromUnitVectors(UP, d.divideScalar(len)));
      this.body.scale.set(r, len, r);
    }
  }
}

function polyline(color: number, dashed = false): Line {
  const g = new BufferGeometry();
  g.setAttribute('position', new Float32BufferAttribute(new Float32Array(6), 3));
  const m = dashed
    ? new LineDashedMaterial({ color, dashSize: 0.02, gapSize: 0.015, transparent: true, opacity: 0.6 })
    : new LineBasicMaterial({ color });
  const l = new Line(g, m);
  l.frustumCulled = false;
  return l;
}

function setLine(l: Line, pts: Float32Array): void {
  l.geometry.setAttribute('position', new Float32BufferAttribute(pts, 3));
  l.geometry.setDrawRange(0, pts.length / 3);
  if (l.material instanceof LineDashedMaterial) l.computeLineDistances();
}

export class ArmView {
  readonly renderer: WebGLRenderer;
  private readonly scene = new Scene();
  private readonly camera = new PerspectiveCamera(40, 1, 0.01, 50);
  private readonly controls: OrbitControls;
  private readonly cyl = new CylinderGeometry(1, 1, 1, 20, 1);
  private readonly sph = new SphereGeometry(1, 20, 14);
  private readonly linkMat = new MeshStandardMaterial({ color: 0x64748b, metalness: 0.2, roughness: 0.55 });
  private readonly toolMat = new MeshStandardMaterial({ color: 0x1e293b, metalness: 0.3, roughness: 0.5 });
  private readonly handMat = new MeshStandardMaterial({ color: 0xf97316, roughness: 0.7 });
  private readonly links: CapsuleMesh[] = [];
  private readonly forearm: CapsuleMesh;
  private readonly handBall: Mesh;
  private readonly goal: Mesh;
  private readonly start: Mesh;
  private readonly tool = polyline(0x2563eb);
  private readonly toolPts: Points;
  private readonly handPath = polyline(0xea580c);
  private readonly handScript = polyline(0xea580c, true);
  private readonly preds: Mesh[] = [];
  private readonly predMats = [
    new MeshStandardMaterial({ color: 0xdb2777, transparent: true, opacity: 0.16, depthWrite: false }),
    new MeshStandardMaterial({ color: 0xdb2777, transparent: true, opacity: 0.08, depthWrite: false }),
  ];
  private readonly cands: Points;
  private readonly chosen: Mesh;
  showPredictions = true;
  showCandidates = true;
  private dirty = true;
  /** Called with the new target while the user Shift-drags it. */
  onTargetDrag: ((x: number, y: number, z: number) => void) | null = null;

  constructor(private readonly host: HTMLElement) {
    this.renderer = new WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2));
    this.renderer.setClearColor(new Color(0xeef2f7));
    host.appendChild(this.renderer.domElement);
    this.camera.up.set(0, 0, 1);
    this.camera.position.set(0.1, -1.2, 2.0);
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.target.set(0.5, 0.12, 0.85);
    this.controls.enableDamping = false;
    this.controls.addEventListener('change', () => (this.dirty = true));
    this.controls.update();

    this.scene.add(new AmbientLight(0xffffff, 1.1));
    const sun = new DirectionalLight(0xffffff, 1.6);
    sun.position.set(-1, -2, 3);
    this.scene.add(sun);
    const grid = new GridHelper(3, 30, 0x94a3b8, 0xcbd5e1);
    grid.rotation.x = Math.PI / 2; // into the z = 0 floor
    grid.position.set(0.5, 0, 0);
    this.scene.add(grid);
    // The floor's reference at table height (the scene's work plane).
    const table = new GridHelper(1.2, 12, 0xb6c2d1, 0xdbe3ec);
    table.rotation.x = Math.PI / 2;
    table.position.set(0.8, 0.15, 0.72);
    this.scene.add(table);

    this.forearm = new CapsuleMesh(this.cyl, this.sph, this.handMat);
    this.handBall = new Mesh(this.sph, this.handMat);
    this.goal = new Mesh(this.sph, new MeshStandardMaterial({ color: 0x16a34a, emissive: 0x14532d }));
    this.goal.scale.setScalar(0.025);
    this.start = new Mesh(this.sph, new MeshStandardMaterial({ color: 0x94a3b8 }));
    this.start.scale.setScalar(0.014);
    this.scene.add(this.forearm.group, this.handBall, this.goal, this.start, this.tool, this.handPath, this.handScript);
    const tg = new BufferGeometry();
    tg.setAttribute('position', new Float32BufferAttribute(new Float32Array(3), 3));
    this.toolPts = new Points(tg, new PointsMaterial({ color: 0x2563eb, size: 5, sizeAttenuation: false }));
    this.toolPts.frustumCulled = false;
    this.scene.add(this.toolPts);
    const cg = new BufferGeometry();
    cg.setAttribute('position', new Float32BufferAttribute(new Float32Array(3), 3));
    this.cands = new Points(cg, new PointsMaterial({ color: 0xa855f7, size: 6, sizeAttenuation: false }));
    this.cands.frustumCulled = false;
    this.chosen = new Mesh(this.sph, new MeshStandardMaterial({ color: 0x7e22ce }));
    this.chosen.scale.setScalar(0.008);
    this.scene.add(this.cands, this.chosen);

    new ResizeObserver(() => this.resize()).observe(host);
    this.resize();
    this.installTargetDrag();
  }

  private resize(): void {
    const w = Math.max(1, this.host.clientWidth);
    const h = Math.max(1, this.host.clientHeight);
    this.renderer.setSize(w, h, false);
    this.renderer.domElement.style.width = '100%';
    this.renderer.domElement.style.height = '100%';
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.dirty = true;
  }

  /** Shift + drag moves the target in its horizontal plane. */
  private installTargetDrag(): void {
    const el = this.renderer.domElement;
    const ray = new Raycaster();
    let plane: Plane | null = null;
    const hit = (ev: PointerEvent): Vector3 | null => {
      const r = el.getBoundingClientRect();
      const ndc = new Vector2(((ev.clientX - r.left) / r.width) * 2 - 1, -((ev.clientY - r.top) / r.height) * 2 + 1);
      ray.setFromCamera(ndc, this.camera);
      const out = new Vector3();
      return plane && ray.ray.intersectPlane(plane, out) ? out : null;
    };
    el.addEventListener('pointerdown', (ev) => {
      if (!ev.shiftKey) return;
      plane = new Plane(new Vector3(0, 0, 1), -this.goal.position.z);
      this.controls.enabled = false;
      el.setPointerCapture(ev.pointerId);
    });
    el.addEventListener('pointermove', (ev) => {
      if (!plane) return;
      const p = hit(ev);
      if (p) this.onTargetDrag?.(p.x, p.y, this.goal.position.z);
    });
    const end = () => {
      plane = null;
      this.controls.enabled = true;
    };
    el.addEventListener('pointerup', end);
    el.addEventListener('pointercancel', end);
  }

  update(f: Frame, showScript: boolean, script: Float32Array): void {
    const n = f.links.length / 7;
    while (this.links.length < n) {
      const c = new CapsuleMesh(this.cyl, this.sph, this.links.length === n - 1 ? this.toolMat : this.linkMat);
      this.links.push(c);
      this.scene.add(c.group);
    }
    for (let i = 0; i < this.links.length; i++) {
      const c = this.links[i];
      c.group.visible = i < n;
      if (i >= n) continue;
      const o = i * 7;
      const L = f.links;
      c.set(new Vector3(L[o], L[o + 1], L[o + 2]), new Vector3(L[o + 3], L[o + 4], L[o + 5]), L[o + 6]);
    }
    const H = f.hand;
    this.handBall.position.set(H[0], H[1], H[2]);
    this.handBall.scale.setScalar(H[3]);
    this.forearm.set(new Vector3(H[4], H[5], H[6]), new Vector3(H[7], H[8], H[9]), H[10]);
    this.goal.position.set(f.goal[0], f.goal[1], f.goal[2]);
    this.start.position.set(f.start[0], f.start[1], f.start[2]);
    setLine(this.tool, f.toolPath);
    this.toolPts.geometry.setAttribute('position', new Float32BufferAttribute(f.toolPath, 3));
    setLine(this.handPath, f.handPath);
    this.handScript.visible = showScript;
    if (showScript) setLine(this.handScript, script);

    const np = this.showPredictions ? f.predictions.length / 5 : 0;
    while (this.preds.length < np) {
      const m = new Mesh(this.sph, this.predMats[0]);
      m.renderOrder = 2;
      this.preds.push(m);
      this.scene.add(m);
    }
    for (let i = 0; i < this.preds.length; i++) {
      const m = this.preds[i];
      m.visible = i < np;
      if (i >= np) continue;
      const P = f.predictions;
      const o = i * 5;
      m.position.set(P[o], P[o + 1], P[o + 2]);
      m.scale.setScalar(P[o + 3]);
      m.material = this.predMats[P[o + 4] > 1.5 ? 1 : 0];
    }
    const showC = this.showCandidates && f.candidates.length > 0;
    this.cands.visible = showC;
    this.chosen.visible = showC && f.chosen >= 0;
    if (showC) {
      this.cands.geometry.setAttribute('position', new Float32BufferAttribute(f.candidates, 3));
      if (f.chosen >= 0) {
        const o = f.chosen * 3;
        this.chosen.position.set(f.candidates[o], f.candidates[o + 1], f.candidates[o + 2]);
      }
    }
    this.dirty = true;
  }

  render(): void {
    if (!this.dirty) return;
    this.dirty = false;
    this.renderer.render(this.scene, this.camera);
  }
}
