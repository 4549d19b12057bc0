// The arm page's 3D view (three.js, z up), fed from the core's draw list of
// the episode: link capsules, the target, the tool path, the hand and
// forearm with their path, script and predicted positions, and the sampled
// step candidates. It only poses three.js objects from the list's numbers;
// only the named three.js classes are imported so the bundle keeps what it
// uses.

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
import { Layer, Shape, type DrawList, type LayerCode } from '../scene/draw';

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
  setMaterial(m: MeshStandardMaterial): void {
    for (const part of [this.body, this.capA, this.capB]) part.material = m;
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

const NONE = new Float64Array(0);

/** The numbers of the first item of layer `l` with `tag`, or none. */
function itemOf(d: DrawList, l: LayerCode, tag = 0): Float64Array {
  const i = d.find(l, tag);
  return i < 0 ? NONE : d.numbers(i);
}

function setLine(l: Line, pts: ArrayLike<number>): void {
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
  /** RRT-Connect's plan still ahead, the tool along it (dashed). */
  private readonly plan = polyline(0x16a34a, true);
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
    this.scene.add(this.forearm.group, this.handBall, this.goal, this.start, this.tool, this.plan, this.handPath, this.handScript);
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

  /** Poses the scene from draw list `d` (the HandPath layer's script,
   *  `tag` 1, shows when the list has it). */
  update(d: DrawList): void {
    const n = d.count(Layer.Links);
    while (this.links.length < n) {
      const c = new CapsuleMesh(this.cyl, this.sph, this.linkMat);
      this.links.push(c);
      this.scene.add(c.group);
    }
    for (let i = 0; i < this.links.length; i++) {
      const c = this.links[i];
      c.group.visible = i < n;
      if (i >= n) continue;
      const k = d.first(Layer.Links) + i;
      const L = d.numbers(k);
      // The tool (value 1) is darker.
      c.setMaterial(d.value(k) === 1 ? this.toolMat : this.linkMat);
      c.set(new Vector3(L[0], L[1], L[2]), new Vector3(L[3], L[4], L[5]), L[6]);
    }
    for (let i = d.first(Layer.Hand); i < d.end(Layer.Hand); i++) {
      const H = d.numbers(i);
      if (d.shape(i) === Shape.Spheres) {
        this.handBall.position.set(H[0], H[1], H[2]);
        this.handBall.scale.setScalar(H[3]);
      } else this.forearm.set(new Vector3(H[0], H[1], H[2]), new Vector3(H[3], H[4], H[5]), H[6]);
    }
    const start = itemOf(d, Layer.Goals, 0);
    const goal = itemOf(d, Layer.Goals, 1);
    if (goal.length === 3) this.goal.position.set(goal[0], goal[1], goal[2]);
    if (start.length === 3) this.start.position.set(start[0], start[1], start[2]);
    const tool = itemOf(d, Layer.Trail);
    setLine(this.tool, tool);
    const plan = itemOf(d, Layer.Trail, 1);
    this.plan.visible = plan.length > 0;
    if (plan.length) setLine(this.plan, plan);
    this.toolPts.geometry.setAttribute('position', new Float32BufferAttribute(tool, 3));
    setLine(this.handPath, itemOf(d, Layer.HandPath, 0));
    const script = itemOf(d, Layer.HandPath, 1);
    this.handScript.visible = script.length > 0;
    if (script.length) setLine(this.handScript, script);

    const np = this.showPredictions ? d.count(Layer.Predicted) : 0;
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
      const k = d.first(Layer.Predicted) + i;
      const P = d.numbers(k);
      m.position.set(P[0], P[1], P[2]);
      m.scale.setScalar(P[3]);
      m.material = this.predMats[d.tag(k) > 1.5 ? 1 : 0];
    }
    const nc = d.count(Layer.Candidates);
    const showC = this.showCandidates && nc > 0;
    const chosen = d.find(Layer.Candidates, 1);
    this.cands.visible = showC;
    this.chosen.visible = showC && chosen >= 0;
    if (showC) {
      const c0 = d.first(Layer.Candidates);
      // One point per item, back to back in the data.
      const pts = d.data.subarray(d.start(c0), d.stop(c0 + nc - 1));
      this.cands.geometry.setAttribute('position', new Float32BufferAttribute(pts, 3));
      if (chosen >= 0) {
        const p = d.numbers(chosen);
        this.chosen.position.set(p[0], p[1], p[2]);
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
