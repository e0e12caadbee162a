//! The cut scene as a glTF 2.0 document: what Preview mode draws, as meshes a 3D viewer, Blender
//! or a web page can open.
//!
//! Layout of the document:
//! - One root node, `cutaway scene`, holding the axis and unit conversion (below); its children
//!   are one node per visible model (structure), named after the model, with one mesh of the same
//!   name.
//! - Each structure's mesh has one primitive per drawn part: the kept surface (the model's colour
//!   and opacity), the walls (their own material: the model's colour leaning toward the wall tint,
//!   as the renderer draws them), the removed piece when the cutter's Transparency view is on
//!   (the model's colour at the cutter's opacity, blended, two-sided), ribbons (two-sided) and
//!   slice walls (wall material), and the contour as a `LINES` primitive (contour material).
//!   A wireframe model is exported as `LINES` of its edges.
//! - Triangle primitives carry `POSITION` and `NORMAL` (area-weighted vertex normals of that
//!   part) and `u32` indices.
//!
//! Units and axes: the vertex data stay in the scene's coordinates, millimetres in the anatomy's
//! Z-up RAS frame (x right, y anterior, z superior), so every exported position is the scene's
//! position rounded to `f32`. The root node converts them to glTF's frame: it scales by 0.001
//! (glTF units are metres, so a knee opens 0.3 units tall, a sane size in three.js and Blender) and
//! rotates (x, y, z) ↦ (−x, z, y), a proper rotation (180° about (0, 1, 1)/√2) that puts superior
//! on glTF's +Y up, anterior on +Z (the front of a glTF asset faces +Z) and the patient's right on
//! −X (glTF's right side of the asset).
//!
//! With an image on the walls (the scene's [`crate::scene::ImageLayer`]), walls, slices and
//! ribbons that show it are subdivided and carry the image as `COLOR_0` on a white `image`
//! material ([`super::image_colors`]). With the risk map on, each cutter's walls are the refined
//! walls of [`crate::cutting::wall_risk`] carrying the map's colours as `COLOR_0` on a white
//! `risk map` material ([`super::risk_colors`]; beyond the far distance the wall colour, or the
//! image where the walls show it).
//!
//! Colours: the scene's colours are sRGB; glTF's `baseColorFactor` is linear, so they are
//! converted. Materials are dielectric (metallic 0) with a matte roughness.

use std::collections::{BTreeMap, HashMap};

use csg::Mesh;
use glam::DVec3;
use gltf_json as json;
use json::validation::{Checked::Valid, USize64};

use crate::cutting::cut_scene::{PartKind, PreviewGeometry, select};
use crate::cutting::wall_risk::WallRisk;
use crate::render::{CONTOUR_COLOR, WALL_MIX, WALL_TINT, srgb_to_linear};
use crate::scene::{ModelStyle, Scene};

/// Name of the root node that carries the unit and axis conversion.
pub const ROOT_NODE_NAME: &str = "cutaway scene";
/// Scale of the root node: scene millimetres to glTF metres.
pub const METRES_PER_MM: f32 = 0.001;
/// Rotation of the root node as a glTF quaternion `[x, y, z, w]`: 180° about (0, 1, 1)/√2, which
/// maps (x, y, z) to (−x, z, y).
pub const Z_UP_TO_Y_UP: [f32; 4] = [
    0.0,
    std::f32::consts::FRAC_1_SQRT_2,
    std::f32::consts::FRAC_1_SQRT_2,
    0.0,
];
/// Roughness of every material (matte, like the renderer's shading).
const ROUGHNESS: f32 = 0.65;

/// What went into a document (for `--json` and the tests).
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct ExportStats {
    /// Structure nodes (one per visible model).
    pub nodes: usize,
    pub materials: usize,
    /// Triangles of all triangle primitives.
    pub triangles: usize,
    /// Line segments of all `LINES` primitives (contours and wireframes).
    pub lines: usize,
}

/// A glTF document and its binary buffer (the BIN chunk of a `.glb`).
#[derive(Debug)]
pub struct Document {
    pub root: json::Root,
    pub bin: Vec<u8>,
    pub stats: ExportStats,
    /// What each material of `root.materials` draws, by material index (a viewer that shades
    /// walls or removed pieces its own way reads this instead of parsing material names).
    pub materials: Vec<MaterialRole>,
}

/// What a material draws.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub struct MaterialRole {
    pub part: MaterialPart,
    /// The scene model whose colour it carries (`None` for the contour and image materials,
    /// which several models share).
    pub model: Option<usize>,
}

/// The kind of geometry a material draws.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum MaterialPart {
    /// A model's own surface (kept part, uncut model, wireframe edges).
    Surface,
    /// Cut walls, slice walls and scalpel incision walls.
    Wall,
    /// The removed piece, translucent.
    Removed,
    Ribbon,
    /// Contour lines where walls meet the surface.
    Contour,
    /// Walls, slices and ribbons showing the intensity image in their vertex colours.
    Image,
    /// Walls showing the risk map in their vertex colours.
    Risk,
}

/// The material a primitive uses; the key that shares one material between primitives.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum MaterialKey {
    /// The model's own surface at its opacity.
    Surface(usize),
    Wall(usize),
    /// The removed piece at an opacity (bits of the `f32`).
    Removed(usize, u32),
    Ribbon(usize),
    Contour,
    /// Walls, slices and ribbons showing the image in their vertex colours.
    Image,
    /// Walls showing the risk map in their vertex colours.
    Risk,
}

/// Builds the document of `scene` as drawn with `geometry` (its [`crate::cutting::cut_scene::preview_geometry`])
/// and, when the risk map is on, `risk` (its [`crate::cutting::wall_risk::wall_risk`]).
pub fn scene_document(
    scene: &Scene,
    geometry: &PreviewGeometry,
    risk: Option<&WallRisk>,
) -> Document {
    let mut builder = Builder::default();
    let mut children = Vec::new();
    for (m, model) in scene.models.iter().enumerate() {
        if !model.visible {
            continue;
        }
        let mut primitives = Vec::new();
        let replaced = geometry.replaced.get(m).copied().unwrap_or(false);
        let walls = model.wall_faces();
        if !replaced && walls.is_empty() {
            primitives.extend(builder.surface(
                scene,
                m,
                &model.model.mesh,
                MaterialKey::Surface(m),
            ));
        } else if !replaced {
            // A scalpel-cut model: its incision walls in the walls' material, on vertices of
            // their own (a hard edge at the lips), as the view draws them.
            let is_wall = |t: usize| walls.binary_search(&(t as u32)).is_ok();
            let surface = select(&model.model.mesh, |t| !is_wall(t)).compacted();
            let incision = select(&model.model.mesh, is_wall).compacted();
            primitives.extend(builder.surface(scene, m, &surface, MaterialKey::Surface(m)));
            primitives.extend(builder.surface(scene, m, &incision, MaterialKey::Wall(m)));
        }
        for part in geometry.parts.iter().filter(|p| p.model == m) {
            if let Some((wall, r)) = risk.and_then(|r| r.wall_for(part).map(|w| (w, r))) {
                let base = mix(model.color, WALL_TINT, WALL_MIX);
                let baked = super::risk_colors::bake(
                    wall,
                    &part.mesh,
                    &r.settings,
                    image_on(scene, part.kind),
                    base,
                );
                primitives.extend(builder.colored_surface(
                    scene,
                    &baked.mesh,
                    &baked.colors,
                    Some(&baked.normals),
                    MaterialKey::Risk,
                ));
                continue;
            }
            if let Some(layer) = image_on(scene, part.kind) {
                let base = match part.kind {
                    PartKind::Ribbon => model.color,
                    _ => mix(model.color, WALL_TINT, WALL_MIX),
                };
                let (mesh, colors) = super::image_colors::bake(&part.mesh, layer, base);
                primitives.extend(builder.colored_surface(
                    scene,
                    &mesh,
                    &colors,
                    None,
                    MaterialKey::Image,
                ));
                continue;
            }
            let key = match part.kind {
                PartKind::Kept => MaterialKey::Surface(m),
                PartKind::Wall | PartKind::SliceWall => MaterialKey::Wall(m),
                PartKind::Removed => MaterialKey::Removed(m, part.opacity.to_bits()),
                PartKind::Ribbon => MaterialKey::Ribbon(m),
            };
            primitives.extend(builder.surface(scene, m, &part.mesh, key));
        }
        let contour: Vec<&[DVec3]> = geometry
            .contours
            .iter()
            .filter(|(model, _)| *model == m)
            .map(|(_, line)| line.as_slice())
            .collect();
        primitives.extend(builder.polylines(scene, &contour, MaterialKey::Contour));
        let mesh = (!primitives.is_empty()).then(|| {
            builder.root.push(json::Mesh {
                extensions: None,
                extras: Default::default(),
                name: Some(model.model.name.clone()),
                primitives,
                weights: None,
            })
        });
        children.push(builder.root.push(json::Node {
            mesh,
            name: Some(model.model.name.clone()),
            ..Default::default()
        }));
        builder.stats.nodes += 1;
    }
    let root_node = builder.root.push(json::Node {
        children: (!children.is_empty()).then_some(children),
        name: Some(ROOT_NODE_NAME.to_string()),
        rotation: Some(json::scene::UnitQuaternion(Z_UP_TO_Y_UP)),
        scale: Some([METRES_PER_MM; 3]),
        ..Default::default()
    });
    let scene_index = builder.root.push(json::Scene {
        extensions: None,
        extras: Default::default(),
        name: Some("cutaway".to_string()),
        nodes: vec![root_node],
    });
    builder.root.scene = Some(scene_index);
    builder.root.asset = json::Asset {
        generator: Some(format!("cutaway {}", env!("CARGO_PKG_VERSION"))),
        ..Default::default()
    };
    if !builder.bin.is_empty() {
        builder.root.buffers.push(json::Buffer {
            byte_length: USize64::from(builder.bin.len()),
            name: None,
            uri: None,
            extensions: None,
            extras: Default::default(),
        });
    }
    builder.stats.materials = builder.root.materials.len();
    Document {
        root: builder.root,
        bin: builder.bin,
        stats: builder.stats,
        materials: builder.roles,
    }
}

/// The image layer a part of `kind` shows, if any (walls; slices and ribbons).
fn image_on(scene: &Scene, kind: PartKind) -> Option<&crate::scene::ImageLayer> {
    let layer = scene.image.as_ref()?;
    let shown = match kind {
        PartKind::Wall => layer.on_walls,
        PartKind::SliceWall => layer.on_walls || layer.on_slices,
        PartKind::Ribbon => layer.on_slices,
        PartKind::Kept | PartKind::Removed => false,
    };
    (shown && layer.display != crate::scene::WallDisplay::Color).then_some(layer)
}

/// Accumulates the JSON objects and the binary buffer.
#[derive(Default)]
struct Builder {
    root: json::Root,
    bin: Vec<u8>,
    materials: HashMap<MaterialKey, json::Index<json::Material>>,
    /// One per material of `root.materials`, in order.
    roles: Vec<MaterialRole>,
    stats: ExportStats,
}

impl Builder {
    /// The primitive of a triangle mesh drawn with `key`'s material (none for an empty mesh); a
    /// wireframe model's own surface becomes `LINES` of its edges.
    fn surface(
        &mut self,
        scene: &Scene,
        model: usize,
        mesh: &Mesh,
        key: MaterialKey,
    ) -> Option<json::mesh::Primitive> {
        if mesh.triangles.is_empty() {
            return None;
        }
        if key == MaterialKey::Surface(model) && scene.models[model].style == ModelStyle::Wireframe
        {
            return self.edges(scene, mesh, key);
        }
        let positions = self.positions(&mesh.positions);
        let normals = self.normals(mesh);
        let indices = self.indices(mesh.triangles.iter().flatten().copied());
        self.stats.triangles += mesh.triangles.len();
        let material = self.material(scene, key);
        Some(primitive(
            positions,
            Some(normals),
            indices,
            material,
            json::mesh::Mode::Triangles,
        ))
    }

    /// A surface whose colours are in its vertices (sRGB per vertex, written linear as glTF
    /// wants) on the white material of `key`: a wall showing the image or the risk map, baked by
    /// [`super::image_colors`] or [`super::risk_colors`].
    fn colored_surface(
        &mut self,
        scene: &Scene,
        mesh: &Mesh,
        colors: &[[f32; 3]],
        normals: Option<&[DVec3]>,
        key: MaterialKey,
    ) -> Option<json::mesh::Primitive> {
        if mesh.triangles.is_empty() {
            return None;
        }
        let positions = self.positions(&mesh.positions);
        let normals = match normals {
            Some(n) => self.normals_of(n),
            None => self.normals(mesh),
        };
        let linear: Vec<[f32; 3]> = colors
            .iter()
            .map(|c| c.map(|v| srgb_to_linear(v.clamp(0.0, 1.0))))
            .collect();
        let colors = self.accessor(
            bytemuck::cast_slice(&linear),
            json::buffer::Target::ArrayBuffer,
            linear.len(),
            json::accessor::ComponentType::F32,
            json::accessor::Type::Vec3,
            None,
        );
        let indices = self.indices(mesh.triangles.iter().flatten().copied());
        self.stats.triangles += mesh.triangles.len();
        let material = self.material(scene, key);
        let mut primitive = primitive(
            positions,
            Some(normals),
            indices,
            material,
            json::mesh::Mode::Triangles,
        );
        primitive
            .attributes
            .insert(Valid(json::mesh::Semantic::Colors(0)), colors);
        Some(primitive)
    }

    /// `LINES` of the unique edges of `mesh`.
    fn edges(
        &mut self,
        scene: &Scene,
        mesh: &Mesh,
        key: MaterialKey,
    ) -> Option<json::mesh::Primitive> {
        let mut edges: Vec<(u32, u32)> = mesh
            .triangles
            .iter()
            .flat_map(|t| (0..3).map(move |k| (t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3]))))
            .collect();
        edges.sort_unstable();
        edges.dedup();
        let positions = self.positions(&mesh.positions);
        let indices = self.indices(edges.iter().flat_map(|&(a, b)| [a, b]));
        self.stats.lines += edges.len();
        let material = self.material(scene, key);
        Some(primitive(
            positions,
            None,
            indices,
            material,
            json::mesh::Mode::Lines,
        ))
    }

    /// One `LINES` primitive of all segments of `lines` (none if there are none).
    fn polylines(
        &mut self,
        scene: &Scene,
        lines: &[&[DVec3]],
        key: MaterialKey,
    ) -> Option<json::mesh::Primitive> {
        let mut points = Vec::new();
        let mut indices = Vec::new();
        for line in lines.iter().filter(|l| l.len() >= 2) {
            let first = points.len() as u32;
            points.extend_from_slice(line);
            for k in 0..line.len() as u32 - 1 {
                indices.extend([first + k, first + k + 1]);
            }
        }
        if indices.is_empty() {
            return None;
        }
        let positions = self.positions(&points);
        self.stats.lines += indices.len() / 2;
        let indices = self.indices(indices.into_iter());
        let material = self.material(scene, key);
        Some(primitive(
            positions,
            None,
            indices,
            material,
            json::mesh::Mode::Lines,
        ))
    }

    /// A `VEC3` `f32` accessor of `points` with its bounds (required for `POSITION`).
    fn positions(&mut self, points: &[DVec3]) -> json::Index<json::Accessor> {
        let data: Vec<[f32; 3]> = points.iter().map(|p| p.as_vec3().to_array()).collect();
        let mut min = [f32::INFINITY; 3];
        let mut max = [f32::NEG_INFINITY; 3];
        for p in &data {
            for k in 0..3 {
                min[k] = min[k].min(p[k]);
                max[k] = max[k].max(p[k]);
            }
        }
        self.accessor(
            bytemuck::cast_slice(&data),
            json::buffer::Target::ArrayBuffer,
            data.len(),
            json::accessor::ComponentType::F32,
            json::accessor::Type::Vec3,
            Some((min, max)),
        )
    }

    /// Area-weighted unit vertex normals of `mesh` (+Z for a vertex whose faces have no area).
    fn normals(&mut self, mesh: &Mesh) -> json::Index<json::Accessor> {
        self.normals_of(&vertex_normals(mesh))
    }

    /// A normal accessor of `normals`, each made unit length (+Z for a zero one).
    fn normals_of(&mut self, normals: &[DVec3]) -> json::Index<json::Accessor> {
        let data: Vec<[f32; 3]> = normals
            .iter()
            .map(|n| {
                let unit = n.try_normalize().unwrap_or(DVec3::Z).as_vec3();
                // Renormalized in f32 so the validator's unit-length check holds after rounding.
                unit.try_normalize().unwrap_or(glam::Vec3::Z).to_array()
            })
            .collect();
        self.accessor(
            bytemuck::cast_slice(&data),
            json::buffer::Target::ArrayBuffer,
            data.len(),
            json::accessor::ComponentType::F32,
            json::accessor::Type::Vec3,
            None,
        )
    }

    /// A `u32` index accessor.
    fn indices(&mut self, indices: impl Iterator<Item = u32>) -> json::Index<json::Accessor> {
        let data: Vec<u32> = indices.collect();
        self.accessor(
            bytemuck::cast_slice(&data),
            json::buffer::Target::ElementArrayBuffer,
            data.len(),
            json::accessor::ComponentType::U32,
            json::accessor::Type::Scalar,
            None,
        )
    }

    /// Appends `bytes` as a buffer view and an accessor over it: `count` elements of
    /// `component` × `type_`, with `bounds` (min, max) where the format requires them.
    fn accessor(
        &mut self,
        bytes: &[u8],
        target: json::buffer::Target,
        count: usize,
        component: json::accessor::ComponentType,
        type_: json::accessor::Type,
        bounds: Option<([f32; 3], [f32; 3])>,
    ) -> json::Index<json::Accessor> {
        let view = self.view(bytes, target);
        self.root.push(json::Accessor {
            buffer_view: Some(view),
            byte_offset: None,
            count: USize64::from(count),
            component_type: Valid(json::accessor::GenericComponentType(component)),
            extensions: None,
            extras: Default::default(),
            type_: Valid(type_),
            min: bounds.map(|(min, _)| serde_json::json!(min)),
            max: bounds.map(|(_, max)| serde_json::json!(max)),
            name: None,
            normalized: false,
            sparse: None,
        })
    }

    /// Appends `bytes` to the buffer (every view starts on a 4-byte boundary) as a buffer view.
    fn view(
        &mut self,
        bytes: &[u8],
        target: json::buffer::Target,
    ) -> json::Index<json::buffer::View> {
        let offset = self.bin.len();
        self.bin.extend_from_slice(bytes);
        self.bin.resize(super::glb::padded_len(self.bin.len()), 0);
        self.root.push(json::buffer::View {
            buffer: json::Index::new(0),
            byte_length: USize64::from(bytes.len()),
            byte_offset: Some(USize64::from(offset)),
            byte_stride: None,
            name: None,
            target: Some(Valid(target)),
            extensions: None,
            extras: Default::default(),
        })
    }

    /// The material of `key`, created on first use.
    fn material(&mut self, scene: &Scene, key: MaterialKey) -> json::Index<json::Material> {
        if let Some(&index) = self.materials.get(&key) {
            return index;
        }
        let name_of = |m: usize| scene.models[m].model.name.clone();
        let (name, srgb, opacity, double_sided) = match key {
            MaterialKey::Surface(m) => (
                name_of(m),
                scene.models[m].color,
                scene.models[m].opacity,
                false,
            ),
            MaterialKey::Wall(m) => (
                format!("{} wall", name_of(m)),
                mix(scene.models[m].color, WALL_TINT, WALL_MIX),
                1.0,
                false,
            ),
            MaterialKey::Removed(m, bits) => (
                format!("{} removed", name_of(m)),
                scene.models[m].color,
                f32::from_bits(bits),
                true,
            ),
            MaterialKey::Ribbon(m) => (
                format!("{} ribbon", name_of(m)),
                scene.models[m].color,
                1.0,
                true,
            ),
            MaterialKey::Contour => ("contour".to_string(), CONTOUR_COLOR, 1.0, false),
            // White: the vertex colours are the image, or the risk map.
            MaterialKey::Image => ("image".to_string(), [1.0; 3], 1.0, false),
            MaterialKey::Risk => ("risk map".to_string(), [1.0; 3], 1.0, false),
        };
        let opacity = opacity.clamp(0.0, 1.0);
        let [r, g, b] = srgb.map(|c| srgb_to_linear(c.clamp(0.0, 1.0)));
        let index = self.root.push(json::Material {
            name: Some(name),
            alpha_mode: Valid(if opacity < 1.0 {
                json::material::AlphaMode::Blend
            } else {
                json::material::AlphaMode::Opaque
            }),
            double_sided,
            pbr_metallic_roughness: json::material::PbrMetallicRoughness {
                base_color_factor: json::material::PbrBaseColorFactor([r, g, b, opacity]),
                metallic_factor: json::material::StrengthFactor(0.0),
                roughness_factor: json::material::StrengthFactor(ROUGHNESS),
                ..Default::default()
            },
            ..Default::default()
        });
        self.materials.insert(key, index);
        self.roles.push(key.role());
        index
    }
}

/// Area-weighted vertex normals of `mesh` (sums of the faces' scaled normals, not unit length).
pub fn vertex_normals(mesh: &Mesh) -> Vec<DVec3> {
    let mut sums = vec![DVec3::ZERO; mesh.positions.len()];
    for t in 0..mesh.triangles.len() {
        let n = mesh.face_normal_scaled(t);
        for &v in &mesh.triangles[t] {
            sums[v as usize] += n;
        }
    }
    sums
}

impl MaterialKey {
    fn role(self) -> MaterialRole {
        let (part, model) = match self {
            MaterialKey::Surface(m) => (MaterialPart::Surface, Some(m)),
            MaterialKey::Wall(m) => (MaterialPart::Wall, Some(m)),
            MaterialKey::Removed(m, _) => (MaterialPart::Removed, Some(m)),
            MaterialKey::Ribbon(m) => (MaterialPart::Ribbon, Some(m)),
            MaterialKey::Contour => (MaterialPart::Contour, None),
            MaterialKey::Image => (MaterialPart::Image, None),
            MaterialKey::Risk => (MaterialPart::Risk, None),
        };
        MaterialRole { part, model }
    }
}

fn mix(a: [f32; 3], b: [f32; 3], t: f32) -> [f32; 3] {
    [0, 1, 2].map(|k| a[k] + (b[k] - a[k]) * t)
}

fn primitive(
    positions: json::Index<json::Accessor>,
    normals: Option<json::Index<json::Accessor>>,
    indices: json::Index<json::Accessor>,
    material: json::Index<json::Material>,
    mode: json::mesh::Mode,
) -> json::mesh::Primitive {
    let mut attributes = BTreeMap::new();
    attributes.insert(Valid(json::mesh::Semantic::Positions), positions);
    if let Some(normals) = normals {
        attributes.insert(Valid(json::mesh::Semantic::Normals), normals);
    }
    json::mesh::Primitive {
        attributes,
        extensions: None,
        extras: Default::default(),
        indices: Some(indices),
        material: Some(material),
        mode: Valid(mode),
        targets: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A scalpel-cut model without cutters exports its incision walls as a primitive of their
    /// own in the walls' material; without the marks it is one surface primitive.
    #[test]
    fn incision_walls_export_in_the_wall_material() {
        use crate::cutting::cut_scene::incision_tests::grooved_sphere_cut;
        for marked in [true, false] {
            let (mut scene, walls) = grooved_sphere_cut(marked);
            scene.cutters.clear();
            let geometry = crate::cutting::cut_scene::preview_geometry(&scene);
            let doc = scene_document(&scene, &geometry, None);
            let primitives = &doc.root.meshes[0].primitives;
            let materials: Vec<String> = primitives
                .iter()
                .map(|p| {
                    let m = p.material.expect("a material").value();
                    doc.root.materials[m].name.clone().unwrap_or_default()
                })
                .collect();
            if marked {
                assert_eq!(primitives.len(), 2, "{materials:?}");
                assert_ne!(materials[0], materials[1]);
                let index = primitives[1].indices.expect("indexed").value();
                assert_eq!(doc.root.accessors[index].count.0, 3 * walls.len() as u64);
            } else {
                assert_eq!(primitives.len(), 1, "{materials:?}");
            }
        }
    }
}
