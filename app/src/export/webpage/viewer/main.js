// The page's viewer: loads each variant's glTF with three.js's GLTFLoader, shades it as
// Cutaway's renderer does (shading.js), and gives it the window's navigation: orbit, zoom and pan
// with mouse or touch (OrbitControls), the six standard views, the orientation marker and the
// scale bar (overlays.js), the structure list, variants, removed piece opacity and metrics
// (panels.js). The first view is the session's camera, so the page opens on the picture
// `cutaway render` draws. Frames are drawn on demand (after a change), not in a loop.

import * as THREE from 'three';
import { GLTFLoader } from './GLTFLoader.js';
import { OrbitControls } from './OrbitControls.js';
import { shadeDocument, setOpacity } from './shading.js';
import { OrientationMarker, pixelsPerMm, scaleBar } from './overlays.js';
import * as panels from './panels.js';

const $ = (id) => document.getElementById(id);

/** Starts the viewer; `payloads.scene(k)` inflates variant k's `.glb` bytes. */
export async function start(payloads) {
  const data = JSON.parse($('cutaway-data').textContent);
  const viewer = new Viewer(data, payloads);
  window.cutaway = viewer.testing();
  await viewer.showVariant(data.active_variant);
}

class Viewer {
  constructor(data, payloads) {
    this.data = data;
    this.payloads = payloads;
    this.variant = -1;
    this.documents = new Map();
    this.shown = null;
    this.visible = data.structures.map(() => true);
    this.removedOpacity = null;
    this.frames = 0;
    this.pending = false;
    this.animation = null;

    document.title = data.title;
    $('cutaway-title').textContent = data.title;
    const canvas = $('cutaway-canvas');
    this.canvas = canvas;
    this.renderer = new THREE.WebGLRenderer({ canvas, antialias: false });
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
    this.linear = linearTarget(this.renderer);
    this.scene = new THREE.Scene();
    const [r, g, b] = data.background;
    this.scene.background = new THREE.Color().setRGB(r, g, b, THREE.SRGBColorSpace);
    this.camera = new THREE.PerspectiveCamera(data.camera.fov_y_deg, 1, 0.01, 100);
    this.loader = new GLTFLoader();
    this.marker = new OrientationMarker($('cutaway-marker'), data.orientation);

    this.list = panels.structureList($('cutaway-structure-list'), data.structures, (indices, visible) => {
      for (const i of indices) this.visible[i] = visible;
      this.applyVisibility();
    });
    panels.viewButtons($('cutaway-views'), data.views, (k) => this.goToView(k));
    panels.variantChoice($('cutaway-variant'), data.variants, data.active_variant, (k) => {
      this.showVariant(k).catch(fail);
    });
    this.removed = panels.removedSlider($('cutaway-removed'), $('cutaway-removed-value'), (v) => {
      this.removedOpacity = v;
      this.applyRemovedOpacity();
    });
    this.metrics = panels.metricsTable($('cutaway-metrics-table'), data.metrics, data.variants);
    panels.footer($('cutaway-footer'), data);
    const narrow = window.matchMedia('(max-width: 700px)').matches;
    panels.foldable($('cutaway-structures'), !narrow);
    panels.foldable($('cutaway-measures'), false);
    $('cutaway-show-all').addEventListener('click', () => this.setAll(true));
    $('cutaway-hide-all').addEventListener('click', () => this.setAll(false));

    new ResizeObserver(() => this.resize()).observe($('cutaway-view'));
    this.resize();
    this.pointerEvents();
    window.addEventListener('keydown', (event) => this.key(event));
  }

  /** Loads (once) and shows variant `k`, keeping the view and the structures shown. */
  async showVariant(k) {
    document.body.dataset.state = 'loading';
    let shown = this.documents.get(k);
    if (!shown) {
      status(`Loading ${this.data.variants.length > 1 ? `variant \u201c${this.data.variants[k].name}\u201d` : 'the scene'}\u2026`);
      const bytes = await this.payloads.scene(k);
      const gltf = await this.loader.parseAsync(bytes.buffer, '');
      shown = shadeDocument(gltf, this.data.variants[k], this.data);
      this.documents.set(k, shown);
    }
    if (this.shown) this.scene.remove(this.shown.scene);
    const first = this.shown === null;
    this.shown = shown;
    this.variant = k;
    this.scene.add(shown.scene);
    this.scene.updateMatrixWorld(true);
    if (first) this.setFrame(shown.root);
    this.applyVisibility();
    const session = this.data.variants[k].removed_opacity;
    const opacity = shown.removed.length === 0 ? null : (this.removedOpacity ?? session ?? 0.3);
    this.removed.set(opacity);
    this.applyRemovedOpacity();
    this.metrics.setActive(k);
    $('cutaway-variant').value = String(k);
    document.body.dataset.variant = String(k);
    this.resizeLines();
    await this.nextFrame();
    status(null);
    document.body.dataset.state = 'ready';
  }

  /** The page frame from the glTF root node: scene coordinates → page coordinates. */
  setFrame(root) {
    this.pageFromScene = root.matrixWorld.clone();
    const rotation = new THREE.Quaternion();
    root.matrixWorld.decompose(new THREE.Vector3(), rotation, new THREE.Vector3());
    this.marker.setFrame(rotation);
    const scale = new THREE.Vector3().setFromMatrixScale(root.matrixWorld).x;
    // Millimetres per page unit: page units are scene units scaled by the root node.
    this.mmPerPageUnit = this.data.mm_per_unit / scale;
    const b = this.data.bounds;
    const min = new THREE.Vector3(...b.min);
    const max = new THREE.Vector3(...b.max);
    this.centre = min.clone().add(max).multiplyScalar(0.5).applyMatrix4(this.pageFromScene);
    this.radius = Math.max(0.5 * min.distanceTo(max) * scale, 1e-9);
    this.setCamera(this.pose(this.data.camera));
    this.sessionPose = this.pose(this.data.camera);
  }

  /** A session camera (scene coordinates) as a page pose. */
  pose(c) {
    const eye = new THREE.Vector3(...c.eye).applyMatrix4(this.pageFromScene);
    const target = new THREE.Vector3(...c.target).applyMatrix4(this.pageFromScene);
    const up = new THREE.Vector3(...c.up).transformDirection(this.pageFromScene);
    return { eye, target, up };
  }

  setCamera({ eye, target, up }) {
    this.camera.position.copy(eye);
    this.camera.up.copy(up);
    this.camera.lookAt(target);
    this.camera.updateMatrixWorld();
    this.makeControls(target);
    this.requestRender();
  }

  /** OrbitControls orbit about the camera's up at their creation: made again after a view. */
  makeControls(target) {
    if (this.controls) this.controls.dispose();
    const controls = new OrbitControls(this.camera, this.canvas);
    controls.target.copy(target);
    controls.screenSpacePanning = true;
    controls.zoomToCursor = true;
    controls.minDistance = this.radius * 0.02;
    controls.maxDistance = this.radius * 30;
    controls.update();
    controls.addEventListener('change', () => this.requestRender());
    controls.addEventListener('start', () => this.hideTip());
    this.controls = controls;
  }

  /** View `k` of the six (−1: the session's), reached in a short turn. */
  goToView(k) {
    const pose = k < 0 ? this.sessionPose : this.pose(this.data.views[k].camera);
    const from = {
      target: this.controls.target.clone(),
      distance: this.camera.position.distanceTo(this.controls.target),
      rotation: this.camera.quaternion.clone(),
    };
    const end = new THREE.PerspectiveCamera();
    end.position.copy(pose.eye);
    end.up.copy(pose.up);
    end.lookAt(pose.target);
    const to = { target: pose.target, distance: pose.eye.distanceTo(pose.target), rotation: end.quaternion };
    const started = performance.now();
    const duration = 350;
    this.controls.enabled = false;
    this.animation = (now) => {
      const t = Math.min((now - started) / duration, 1);
      const s = t * t * (3 - 2 * t);
      const rotation = from.rotation.clone().slerp(to.rotation, s);
      const target = from.target.clone().lerp(to.target, s);
      const distance = from.distance * Math.pow(to.distance / from.distance, s);
      this.camera.quaternion.copy(rotation);
      this.camera.position.copy(target).add(new THREE.Vector3(0, 0, distance).applyQuaternion(rotation));
      this.camera.up.set(0, 1, 0).applyQuaternion(rotation);
      this.camera.updateMatrixWorld();
      if (t >= 1) {
        this.animation = null;
        this.setCamera(pose);
      }
    };
    this.requestRender();
  }

  applyVisibility() {
    if (!this.shown) return;
    this.shown.structures.forEach((s, i) => {
      if (s.node) s.node.visible = this.visible[i];
    });
    this.hideTip();
    this.requestRender();
  }

  setAll(visible) {
    this.visible.fill(visible);
    this.visible.forEach((_, i) => this.list.setVisible(i, visible));
    this.applyVisibility();
  }

  applyRemovedOpacity() {
    if (!this.shown) return;
    for (const material of this.shown.removed) {
      // The session's opacity of each removed piece until the slider is moved.
      const v = this.removedOpacity ?? material.userData.sessionOpacity;
      setOpacity(material, v);
      material.visible = v > 0;
    }
    this.requestRender();
  }

  resize() {
    const view = $('cutaway-view');
    const width = Math.max(view.clientWidth, 1);
    const height = Math.max(view.clientHeight, 1);
    this.renderer.setSize(width, height, false);
    this.linear.resize();
    this.camera.aspect = width / height;
    this.camera.fov = fieldOfView(this.data.camera.fov_y_deg, this.camera.aspect);
    this.camera.updateProjectionMatrix();
    this.resizeLines();
    this.requestRender();
  }

  /** Contour lines as wide as the renderer's: 3 px, more in a view over 800 px tall. */
  resizeLines() {
    if (!this.shown) return;
    const height = Math.max($('cutaway-view').clientHeight, 1);
    const width = this.data.style.contour_width_px * Math.max(height / 800, 1);
    for (const material of this.shown.contours) material.linewidth = width;
  }

  requestRender() {
    if (this.pending) return;
    this.pending = true;
    requestAnimationFrame((now) => {
      this.pending = false;
      if (this.animation) {
        this.animation(now);
        this.requestRender();
      }
      this.render();
    });
  }

  /** Resolves once a frame with every change so far is drawn. */
  nextFrame() {
    this.requestRender();
    const frame = this.frames;
    return new Promise((resolve) => {
      const wait = () => (this.frames > frame ? resolve() : requestAnimationFrame(wait));
      requestAnimationFrame(wait);
    });
  }

  render() {
    if (!this.shown) return;
    // The renderer's depth range: the scene's bounding sphere seen from the eye.
    const eye = this.camera.position;
    const distance = eye.distanceTo(this.centre);
    const far = distance + this.radius * 1.05;
    const toTarget = this.controls ? eye.distanceTo(this.controls.target) : distance;
    const closest = Math.max(Math.min(far * 1e-4, 0.25 * toTarget), far * 1e-7);
    this.camera.near = Math.max(distance - this.radius * 1.05, closest);
    this.camera.far = far;
    this.camera.updateProjectionMatrix();
    this.linear.draw(this.scene, this.camera);
    this.marker.draw(this.camera);
    this.drawScaleBar();
    this.frames += 1;
    document.body.dataset.frames = String(this.frames);
  }

  drawScaleBar() {
    const view = $('cutaway-view');
    const target = this.controls ? this.controls.target : this.centre;
    const perMm = pixelsPerMm(this.camera, target, view.clientHeight, this.mmPerPageUnit);
    const bar = scaleBar(perMm, view.clientWidth / 4);
    const box = $('cutaway-scale');
    box.hidden = bar === null;
    if (bar) {
      box.querySelector('.bar').style.width = `${bar.pixels.toFixed(1)}px`;
      box.querySelector('.caption').textContent = bar.caption;
    }
  }

  pointerEvents() {
    const canvas = this.canvas;
    let down = null;
    let timer = 0;
    canvas.addEventListener('pointerdown', (e) => {
      down = { x: e.clientX, y: e.clientY, time: performance.now() };
    });
    canvas.addEventListener('pointerup', (e) => {
      const tap = down && Math.hypot(e.clientX - down.x, e.clientY - down.y) < 6 &&
        performance.now() - down.time < 500;
      down = null;
      if (tap && e.pointerType !== 'mouse') this.showTip(e.clientX, e.clientY, 2500);
    });
    canvas.addEventListener('pointermove', (e) => {
      if (e.pointerType !== 'mouse' || e.buttons !== 0) return;
      clearTimeout(timer);
      this.hideTip();
      timer = setTimeout(() => this.showTip(e.clientX, e.clientY, 0), 80);
    });
    canvas.addEventListener('pointerleave', () => {
      clearTimeout(timer);
      this.hideTip();
    });
  }

  /** The structure drawn at client point (x, y): opaque surfaces first, then translucent. */
  pick(x, y) {
    if (!this.shown) return null;
    const rect = this.canvas.getBoundingClientRect();
    const ndc = new THREE.Vector2(((x - rect.left) / rect.width) * 2 - 1, -((y - rect.top) / rect.height) * 2 + 1);
    const raycaster = new THREE.Raycaster();
    raycaster.setFromCamera(ndc, this.camera);
    const meshes = [];
    this.shown.structures.forEach((s, i) => {
      if (!this.visible[i]) return;
      for (const d of s.drawables) if (d.isMesh && !d.isLineSegments2 && d.material.visible) meshes.push(d);
    });
    const hits = raycaster.intersectObjects(meshes, false);
    const opaque = hits.find((h) => !h.object.material.transparent);
    const hit = opaque ?? hits[0];
    if (!hit) return null;
    const part = hit.object.userData.part;
    return { structure: hit.object.userData.structure, part };
  }

  showTip(x, y, hideAfterMs) {
    const found = this.pick(x, y);
    const tip = $('cutaway-tip');
    if (!found) {
      this.hideTip();
      return;
    }
    const name = this.data.structures[found.structure].name;
    const part = { wall: 'cut surface', removed: 'removed piece', image: 'cut surface', ribbon: 'ribbon' }[found.part];
    tip.textContent = part ? `${name} \u00b7 ${part}` : name;
    tip.hidden = false;
    const box = tip.getBoundingClientRect();
    tip.style.left = `${Math.min(x + 14, window.innerWidth - box.width - 4)}px`;
    tip.style.top = `${Math.max(y - box.height - 10, 4)}px`;
    this.list.highlight(found.structure);
    if (hideAfterMs > 0) setTimeout(() => this.hideTip(), hideAfterMs);
  }

  hideTip() {
    $('cutaway-tip').hidden = true;
    this.list.highlight(-1);
  }

  key(event) {
    if (event.target instanceof HTMLInputElement || event.target instanceof HTMLSelectElement) return;
    const opposite = event.ctrlKey || event.altKey;
    const index = { 1: opposite ? 1 : 0, 3: opposite ? 2 : 3, 7: opposite ? 5 : 4 }[event.key];
    if (index !== undefined) {
      const name = ['Anterior', 'Posterior', 'Left', 'Right', 'Superior', 'Inferior'][index];
      this.goToView(this.data.views.findIndex((v) => v.name === name));
      event.preventDefault();
    } else if (event.key === '0' || event.key === 'Home') {
      this.goToView(-1);
      event.preventDefault();
    }
  }

  /** What tests read: the state, and the structure under a client point. */
  testing() {
    return {
      state: () => ({
        variant: this.variant,
        visible: this.visible.slice(),
        frames: this.frames,
        removedOpacity: this.shown?.removed[0]?.uniforms.opacity.value ?? null,
        structures: this.data.structures.length,
      }),
      pick: (x, y) => this.pick(x, y),
      nextFrame: () => this.nextFrame(),
    };
  }
}

/**
 * The vertical field of view for a view of `aspect` (width / height): the session's, or wider
 * on a view narrower than `cutaway render`'s 1280 × 800 (a phone held upright), so the page shows
 * at least the width the render shows.
 */
function fieldOfView(sessionDeg, aspect) {
  const half = THREE.MathUtils.degToRad(sessionDeg) / 2;
  const widened = 2 * Math.atan(Math.tan(half) * (1280 / 800) / Math.max(aspect, 1e-3));
  return THREE.MathUtils.radToDeg(Math.min(Math.max(2 * half, widened), THREE.MathUtils.degToRad(120)));
}

/**
 * Drawing in linear light, as the renderer does: the scene goes into a multisampled half-float
 * image (so translucent layers blend in linear light, not in the screen's sRGB encoding, which
 * would darken a removed piece over a dark structure), then onto the canvas sRGB-encoded.
 */
function linearTarget(renderer) {
  const gl = renderer.getContext();
  const halfFloat = renderer.extensions.has('EXT_color_buffer_half_float') ||
    renderer.extensions.has('EXT_color_buffer_float');
  const samples = Math.min(4, gl.getParameter(gl.MAX_SAMPLES) || 0);
  const target = new THREE.WebGLRenderTarget(1, 1, {
    type: halfFloat ? THREE.HalfFloatType : THREE.UnsignedByteType,
    samples,
    minFilter: THREE.NearestFilter,
    magFilter: THREE.NearestFilter,
  });
  const output = new THREE.Mesh(
    new THREE.PlaneGeometry(2, 2),
    new THREE.ShaderMaterial({
      uniforms: { image: { value: target.texture } },
      vertexShader: 'varying vec2 vUv; void main() { vUv = uv; gl_Position = vec4(position.xy, 0.0, 1.0); }',
      fragmentShader: 'uniform sampler2D image; varying vec2 vUv;' +
        'void main() { gl_FragColor = linearToOutputTexel(texture2D(image, vUv)); }',
      depthTest: false,
      depthWrite: false,
    }),
  );
  output.frustumCulled = false;
  const screen = new THREE.Scene();
  screen.add(output);
  const screenCamera = new THREE.OrthographicCamera(-1, 1, 1, -1, 0, 1);
  const size = new THREE.Vector2();
  return {
    resize() {
      renderer.getDrawingBufferSize(size);
      target.setSize(Math.max(size.x, 1), Math.max(size.y, 1));
    },
    draw(scene, camera) {
      renderer.setRenderTarget(target);
      renderer.render(scene, camera);
      renderer.setRenderTarget(null);
      renderer.render(screen, screenCamera);
    },
  };
}

function status(text) {
  const s = $('cutaway-status');
  s.hidden = text === null;
  if (text !== null) s.textContent = text;
}

function fail(error) {
  console.error(error);
  const s = $('cutaway-status');
  s.hidden = false;
  s.classList.add('error');
  s.textContent = `The scene could not be shown: ${error && error.message ? error.message : error}`;
  document.body.dataset.state = 'failed';
}
