// What the page draws over the 3D view: the orientation marker (the patient's axes as the
// camera sees them, coloured and labelled as in the window: R/L red, A/P green, S/I blue) and
// the scale bar (a round length in millimetres, exact in the plane through the orbit target).

import * as THREE from 'three';

const AXES = [
  ['R', 'right', 1, '#e6463c'],
  ['L', 'right', -1, '#e6463c'],
  ['A', 'anterior', 1, '#50c85a'],
  ['P', 'anterior', -1, '#50c85a'],
  ['S', 'superior', 1, '#5a8cfa'],
  ['I', 'superior', -1, '#5a8cfa'],
];

/** The marker in a 2-D canvas; `orientation`: the page data's axes (scene coordinates). */
export class OrientationMarker {
  constructor(canvas, orientation) {
    this.canvas = canvas;
    this.context = canvas.getContext('2d');
    this.orientation = orientation;
    this.world = null;
  }

  /** Maps the axes into page coordinates with the glTF root node's rotation. */
  setFrame(rootQuaternion) {
    this.world = AXES.map(([label, field, sign, color]) => ({
      label,
      color,
      positive: sign > 0,
      direction: new THREE.Vector3(...this.orientation[field])
        .multiplyScalar(sign)
        .applyQuaternion(rootQuaternion)
        .normalize(),
    }));
  }

  draw(camera) {
    if (!this.world) return;
    const ratio = window.devicePixelRatio || 1;
    const size = this.canvas.clientWidth;
    if (this.canvas.width !== Math.round(size * ratio)) {
      this.canvas.width = this.canvas.height = Math.round(size * ratio);
    }
    const g = this.context;
    g.setTransform(ratio, 0, 0, ratio, 0, 0);
    g.clearRect(0, 0, size, size);
    const centre = size / 2;
    const radius = size * 0.28;
    g.fillStyle = 'rgba(20, 22, 26, 0.43)';
    g.beginPath();
    g.arc(centre, centre, radius + 14, 0, 2 * Math.PI);
    g.fill();
    const right = new THREE.Vector3().setFromMatrixColumn(camera.matrixWorld, 0);
    const up = new THREE.Vector3().setFromMatrixColumn(camera.matrixWorld, 1);
    const back = new THREE.Vector3().setFromMatrixColumn(camera.matrixWorld, 2);
    const axes = this.world
      .map((a) => ({
        ...a,
        x: a.direction.dot(right),
        y: -a.direction.dot(up),
        depth: a.direction.dot(back),
      }))
      .sort((a, b) => a.depth - b.depth);
    g.textAlign = 'center';
    g.textBaseline = 'middle';
    for (const a of axes) {
      const tip = [centre + a.x * radius, centre + a.y * radius];
      g.strokeStyle = a.positive ? a.color : dim(a.color);
      g.lineWidth = a.positive ? 3 : 1.5;
      g.beginPath();
      g.moveTo(centre, centre);
      g.lineTo(tip[0], tip[1]);
      g.stroke();
      if (a.positive) {
        g.fillStyle = a.color;
        g.beginPath();
        g.arc(tip[0], tip[1], 2.5, 0, 2 * Math.PI);
        g.fill();
      }
      const length = Math.hypot(a.x, a.y);
      const reach = Math.max(length, 0.35) + 0.32;
      const dx = length > 1e-9 ? a.x / length : 0;
      const dy = length > 1e-9 ? a.y / length : 0;
      const front = a.depth > -0.3;
      g.font = `${front ? 14 : 11}px system-ui, sans-serif`;
      g.fillStyle = front ? '#fff' : '#969696';
      g.fillText(a.label, centre + dx * radius * reach, centre + dy * radius * reach);
    }
  }
}

function dim(hex) {
  const n = parseInt(hex.slice(1), 16);
  const c = [n >> 16, (n >> 8) & 255, n & 255].map((v) => Math.round(v * 0.55));
  return `rgb(${c.join(',')})`;
}

/**
 * The longest round length (1, 2 or 5 × 10ⁿ mm) whose bar is at most `maxPixels` long at
 * `pixelsPerMm`, as `cutaway render --labels` chooses it.
 */
export function scaleBar(pixelsPerMm, maxPixels) {
  if (!(pixelsPerMm > 0 && Number.isFinite(pixelsPerMm) && maxPixels > 0)) return null;
  const maxMm = maxPixels / pixelsPerMm;
  const decade = Math.pow(10, Math.floor(Math.log10(maxMm)));
  for (const m of [5, 2, 1]) {
    const mm = m * decade;
    if (mm <= maxMm * (1 + 1e-12)) {
      const caption = mm >= 1 ? `${Math.round(mm)} mm` : `${Number(mm.toPrecision(6))} mm`;
      return { mm, pixels: mm * pixelsPerMm, caption };
    }
  }
  return null;
}

/** Pixels per millimetre at the orbit target's depth in a view `heightPx` CSS pixels tall. */
export function pixelsPerMm(camera, target, heightPx, mmPerPageUnit) {
  const distance = camera.position.distanceTo(target);
  const visible = 2 * distance * Math.tan(THREE.MathUtils.degToRad(camera.fov) / 2);
  return heightPx / (visible * mmPerPageUnit);
}
