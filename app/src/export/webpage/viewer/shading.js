// How the page draws a cut scene: the glTF document's materials replaced by the shading of
// Cutaway's renderer (app/src/render/shaders/mesh.wgsl), so the page shows what `cutaway render`
// shows. Two-sided headlight shading in linear light: a key light from above the eye, a weak
// fill from the eye, a small highlight; back faces darker. Walls showing the image are lit
// gently (image.wgsl). Contours are screen-space lines as thick as the renderer's, pulled toward
// the eye so they win the depth test against the surfaces they lie on.

import * as THREE from 'three';
import { LineSegments2 } from './LineSegments2.js';
import { LineMaterial } from './LineMaterial.js';
import { LineSegmentsGeometry } from './LineSegmentsGeometry.js';

const VERTEX = /* glsl */ `
varying vec3 vPositionInView;
varying vec3 vNormalInView;
#ifdef CUTAWAY_IMAGE
attribute vec3 color;
varying vec3 vImage;
#endif
void main() {
  vec4 positionInView = modelViewMatrix * vec4(position, 1.0);
  vPositionInView = positionInView.xyz;
  vNormalInView = normalMatrix * normal;
#ifdef CUTAWAY_IMAGE
  vImage = color;
#endif
  gl_Position = projectionMatrix * positionInView;
}
`;

const FRAGMENT = /* glsl */ `
uniform vec3 baseColor;
uniform float opacity;
uniform float backFace;
varying vec3 vPositionInView;
varying vec3 vNormalInView;
#ifdef CUTAWAY_IMAGE
varying vec3 vImage;
#endif

// The renderer's light, fixed to the camera: normalize(-forward + 0.5 up - 0.25 right).
const vec3 LIGHT = vec3(-0.2182179, 0.4364358, 0.8728716);

// mesh.wgsl's shade_color: the lighting factor (applied to the base colour) and the highlight.
vec2 light(vec3 n, vec3 toEye) {
  float diffuse = max(dot(n, LIGHT), 0.0);
  float fill = max(dot(n, toEye), 0.0);
  vec3 h = normalize(LIGHT + toEye);
  float specular = pow(max(dot(n, h), 0.0), 40.0) * 0.18;
  return vec2(0.18 + 0.6 * diffuse + 0.24 * fill, specular);
}

void main() {
  vec3 toEye = normalize(-vPositionInView);
  vec3 n = vNormalInView;
  float brightness = 1.0;
  if (dot(n, n) < 1e-12) {
    n = normalize(cross(dFdx(vPositionInView), dFdy(vPositionInView)));
    n *= sign(dot(n, toEye) + 1e-20);
    if (!gl_FrontFacing) brightness = backFace;
  } else {
    n = normalize(n);
    if (!gl_FrontFacing) {
      n = -n;
      brightness = backFace;
    }
  }
  vec2 lit = light(n, toEye) * brightness;
#ifdef CUTAWAY_IMAGE
  // image.wgsl: the scan's grey, lit gently (the mean of the white surface's shading, 30 %).
  float white = lit.x + lit.y;
  vec3 color = vImage * mix(1.0, clamp(white, 0.0, 1.2), 0.3);
#else
  vec3 color = baseColor * lit.x + vec3(lit.y);
#endif
  gl_FragColor = linearToOutputTexel(vec4(color, opacity));
}
`;

/** A surface drawn as the renderer draws it. `color`: linear RGB (a THREE.Color). */
export function surfaceMaterial({ color, opacity, backFace, image }) {
  const transparent = opacity < 1;
  return new THREE.ShaderMaterial({
    uniforms: {
      baseColor: { value: color.clone() },
      opacity: { value: opacity },
      backFace: { value: backFace },
    },
    defines: image ? { CUTAWAY_IMAGE: '' } : {},
    vertexShader: VERTEX,
    fragmentShader: FRAGMENT,
    side: THREE.DoubleSide,
    transparent,
    depthWrite: !transparent,
  });
}

/** Sets a surface material's opacity (the removed piece's slider); 0 hides it. */
export function setOpacity(material, opacity) {
  material.uniforms.opacity.value = opacity;
  const transparent = opacity < 1;
  if (material.transparent !== transparent) {
    material.transparent = transparent;
    material.depthWrite = !transparent;
    material.needsUpdate = true;
  }
}

/** Contour lines: `widthPx` CSS pixels wide, pulled `offset` page units toward the eye. */
export function contourMaterial(color, widthPx, offset) {
  const material = new LineMaterial({ linewidth: widthPx });
  material.color.copy(color);
  material.uniforms.cutawayOffset = { value: offset };
  const end = 'vec4 end = modelViewMatrix * vec4( instanceEnd, 1.0 );';
  if (!material.vertexShader.includes(end)) {
    throw new Error('LineMaterial changed: the contour offset cannot be applied');
  }
  material.vertexShader = 'uniform float cutawayOffset;\n' + material.vertexShader.replace(
    end,
    end + '\nstart.xyz += normalize(-start.xyz) * cutawayOffset;' +
      '\nend.xyz += normalize(-end.xyz) * cutawayOffset;',
  );
  return material;
}

/**
 * Replaces the materials of a loaded glTF (GLTFLoader's result) by the renderer's shading.
 * `variant`: the page data's variant (what each glTF material draws). Returns, per structure,
 * its node and its drawables, plus the removed pieces' materials and the contour materials.
 */
export function shadeDocument(gltf, variant, data) {
  const json = gltf.parser.json;
  // The one root node (`cutaway scene`); its children are the structures in list order.
  const root = gltf.scene.children[0];
  const style = data.style;
  const structures = root.children.map(() => ({ node: null, drawables: [] }));
  const removed = [];
  const contours = [];
  const replaced = new Map();
  root.children.forEach((node, s) => {
    structures[s].node = node;
    const drawables = [];
    node.traverse((object) => {
      if (object.isMesh || object.isLine) drawables.push(object);
    });
    for (const object of drawables) {
      const association = gltf.parser.associations.get(object);
      const primitive = json.meshes[association.meshes].primitives[association.primitives ?? 0];
      const index = primitive.material;
      const role = variant.materials[index];
      const source = object.material;
      if (object.isLine) {
        if (role.part === 'contour') {
          const lines = contourLines(object, source.color, style);
          contours.push(lines.material);
          object.parent.add(lines);
          object.parent.remove(object);
          structures[s].drawables.push(lines);
        } else {
          // A wireframe model: its edges, one pixel, flat in the model's colour.
          structures[s].drawables.push(object);
        }
        continue;
      }
      let material = replaced.get(index);
      if (!material) {
        const opacity = json.materials[index].pbrMetallicRoughness?.baseColorFactor?.[3] ?? 1;
        material = surfaceMaterial({
          color: source.color,
          opacity,
          backFace: style.back_face,
          // Image and risk-map walls carry their colours per vertex.
          image: role.part === 'image' || role.part === 'risk',
        });
        material.name = source.name;
        material.userData.part = role.part;
        replaced.set(index, material);
        material.userData.sessionOpacity = opacity;
        if (role.part === 'removed') removed.push(material);
      }
      source.dispose();
      object.material = material;
      object.userData.structure = s;
      object.userData.part = role.part;
      structures[s].drawables.push(object);
    }
  });
  return { scene: gltf.scene, root, structures, removed, contours };
}

function contourLines(line, color, style) {
  const geometry = new LineSegmentsGeometry();
  const positions = line.geometry.getAttribute('position');
  const index = line.geometry.getIndex();
  const points = new Float32Array(index.count * 3);
  for (let k = 0; k < index.count; k++) {
    const v = index.getX(k);
    points[3 * k] = positions.getX(v);
    points[3 * k + 1] = positions.getY(v);
    points[3 * k + 2] = positions.getZ(v);
  }
  geometry.setPositions(points);
  line.geometry.dispose();
  line.material.dispose();
  // Page units are metres: the root node scales scene units by 1/1000.
  const material = contourMaterial(color, style.contour_width_px, style.contour_offset * 0.001);
  const lines = new LineSegments2(geometry, material);
  lines.computeLineDistances();
  lines.userData.part = 'contour';
  lines.position.copy(line.position);
  lines.quaternion.copy(line.quaternion);
  lines.scale.copy(line.scale);
  lines.name = line.name;
  return lines;
}
