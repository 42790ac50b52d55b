//! A minimal glTF 2.0 binary (GLB) writer: meshes, nodes and flat-coloured materials.
//!
//! The JSON is written with serde_json (its maps are sorted, so the bytes depend on the input
//! only) and the binary chunk is packed here, each buffer view 4-byte aligned. Only what the
//! scenes need: positions (no normals, viewers shade flat), indices, triangles, lines or
//! points, one material per colour, node `extras` for what a viewer may list, a single root
//! node that scales millimetres to metres and turns the model's Z-up into glTF's Y-up
//! (plan-format.md, "The 3D scene").

use std::collections::BTreeMap;

use glam::{DMat3, DQuat, DVec3};
use platener_geom::Frame;
use serde_json::{Value, json};

use super::SceneError;
use super::palette::Colour;

/// `mode` of a primitive: how its indices are read.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Mode {
    /// Pairs of indices, one line each (glTF mode 1).
    Lines,
    /// Triples of indices, one triangle each, counter-clockwise seen from outside (mode 4).
    Triangles,
    /// Every position one point, no indices (mode 0).
    Points,
}

impl Mode {
    /// How many indices make one element (points have none).
    fn per(self) -> usize {
        match self {
            Mode::Lines => 2,
            Mode::Triangles => 3,
            Mode::Points => 0,
        }
    }

    /// glTF's `mode` number.
    fn number(self) -> u32 {
        match self {
            Mode::Points => 0,
            Mode::Lines => 1,
            Mode::Triangles => 4,
        }
    }
}

/// Positions and indices of one mesh, in mm.
#[derive(Debug, Clone, Default)]
pub(crate) struct MeshData {
    /// Vertex positions.
    pub(crate) positions: Vec<DVec3>,
    /// Two or three indices per element, by the mode; none for points.
    pub(crate) indices: Vec<u32>,
}

/// The root node's rotation: -90° about X, turning the model's +Z into glTF's +Y.
const Z_UP_TO_Y_UP: [f64; 4] = [
    -std::f64::consts::FRAC_1_SQRT_2,
    0.0,
    0.0,
    std::f64::consts::FRAC_1_SQRT_2,
];
/// The root node's scale: vertex positions are in mm, glTF's unit is the metre.
const MM_TO_M: f64 = 0.001;
/// `bufferView.target` of vertex data.
const ARRAY_BUFFER: u32 = 34962;
/// `bufferView.target` of index data.
const ELEMENT_ARRAY_BUFFER: u32 = 34963;

/// Collects meshes and nodes, then writes the GLB.
#[derive(Debug, Default)]
pub(crate) struct GlbBuilder {
    bin: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
    meshes: Vec<Value>,
    materials: Vec<Value>,
    material_of: BTreeMap<(Colour, bool), usize>,
    nodes: Vec<Value>,
    /// Triangles over all meshes.
    pub(crate) triangles: usize,
    /// Lines over all meshes.
    pub(crate) lines: usize,
    /// Points over all meshes.
    pub(crate) points: usize,
}

impl GlbBuilder {
    /// The material of a colour, made on first use; `double_sided` for surfaces as read
    /// (which may be open or wound inconsistently), not for our closed solids.
    fn material(&mut self, colour: Colour, double_sided: bool) -> usize {
        let next = self.materials.len();
        *self.material_of.entry((colour, double_sided)).or_insert_with(|| {
            let [r, g, b] = colour.linear();
            self.materials.push(json!({
                "name": format!("{}{}", colour.name(), if double_sided { "-surface" } else { "" }),
                "pbrMetallicRoughness": {
                    "baseColorFactor": [r, g, b, 1.0],
                    "metallicFactor": 0.0,
                    "roughnessFactor": 0.8,
                },
                "doubleSided": double_sided,
            }));
            next
        })
    }

    /// Appends bytes as one buffer view (4-byte aligned) and returns its index.
    fn view(&mut self, bytes: &[u8], target: u32) -> usize {
        let offset = self.bin.len();
        self.bin.extend_from_slice(bytes);
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        self.views.push(json!({
            "buffer": 0, "byteOffset": offset, "byteLength": bytes.len(), "target": target,
        }));
        self.views.len() - 1
    }

    /// Adds a mesh of one primitive; `None` when it has nothing to draw (glTF forbids empty
    /// accessors).
    pub(crate) fn mesh(
        &mut self,
        name: &str,
        data: &MeshData,
        mode: Mode,
        colour: Colour,
        double_sided: bool,
    ) -> Result<Option<usize>, SceneError> {
        self.mesh_of(name, &[(data, mode)], colour, double_sided)
    }

    /// Adds a mesh of several primitives in one colour (a surface and its sample points), the
    /// empty ones left out; `None` when none has anything to draw.
    pub(crate) fn mesh_of(
        &mut self,
        name: &str,
        parts: &[(&MeshData, Mode)],
        colour: Colour,
        double_sided: bool,
    ) -> Result<Option<usize>, SceneError> {
        let drawn: Vec<(&MeshData, Mode)> = parts.iter().copied().filter(|(d, m)| drawable(d, *m)).collect();
        if drawn.is_empty() {
            return Ok(None);
        }
        let material = self.material(colour, double_sided);
        let primitives = drawn
            .into_iter()
            .map(|(data, mode)| self.primitive(name, data, mode, material))
            .collect::<Result<Vec<Value>, SceneError>>()?;
        self.meshes.push(json!({ "name": name, "primitives": primitives }));
        Ok(Some(self.meshes.len() - 1))
    }

    /// One primitive's JSON with its accessors written.
    fn primitive(&mut self, name: &str, data: &MeshData, mode: Mode, material: usize) -> Result<Value, SceneError> {
        let count = u32::try_from(data.positions.len()).map_err(|_| SceneError::TooLarge { what: name.into() })?;
        let per = mode.per();
        let fits = match mode {
            Mode::Points => data.indices.is_empty(),
            _ => data.indices.iter().all(|&i| i < count) && data.indices.len().is_multiple_of(per),
        };
        if !fits {
            return Err(SceneError::Bug(format!("mesh {name}: indices do not fit its vertices")));
        }
        let position = self.positions(&data.positions);
        let mut primitive = json!({
            "attributes": { "POSITION": position },
            "material": material,
            "mode": mode.number(),
        });
        match mode {
            Mode::Lines => self.lines += data.indices.len() / 2,
            Mode::Triangles => self.triangles += data.indices.len() / 3,
            Mode::Points => self.points += data.positions.len(),
        }
        if mode != Mode::Points {
            primitive["indices"] = json!(self.indices(&data.indices, count));
        }
        Ok(primitive)
    }

    /// The POSITION accessor (f32 VEC3) with the min/max glTF requires, taken from the f32
    /// values actually stored.
    fn positions(&mut self, positions: &[DVec3]) -> usize {
        let mut lo = [f32::INFINITY; 3];
        let mut hi = [f32::NEG_INFINITY; 3];
        let mut bytes = Vec::with_capacity(positions.len() * 12);
        for p in positions {
            let q = p.as_vec3().to_array();
            for k in 0..3 {
                lo[k] = lo[k].min(q[k]);
                hi[k] = hi[k].max(q[k]);
                bytes.extend_from_slice(&q[k].to_le_bytes());
            }
        }
        let view = self.view(&bytes, ARRAY_BUFFER);
        self.accessors.push(json!({
            "bufferView": view, "componentType": 5126, "count": positions.len(), "type": "VEC3",
            "min": lo, "max": hi,
        }));
        self.accessors.len() - 1
    }

    /// The index accessor: u16 when the vertices allow (half the bytes), else u32.
    fn indices(&mut self, indices: &[u32], vertex_count: u32) -> usize {
        let (bytes, component) = if vertex_count <= u32::from(u16::MAX) {
            let b: Vec<u8> = indices.iter().flat_map(|&i| (i as u16).to_le_bytes()).collect();
            (b, 5123)
        } else {
            (indices.iter().flat_map(|&i| i.to_le_bytes()).collect(), 5125)
        };
        let view = self.view(&bytes, ELEMENT_ARRAY_BUFFER);
        self.accessors.push(json!({
            "bufferView": view, "componentType": component, "count": indices.len(), "type": "SCALAR",
        }));
        self.accessors.len() - 1
    }

    /// Adds a child of the root: a named node drawing `mesh`, placed by `frame` (local →
    /// model) when given.
    pub(crate) fn node(&mut self, name: &str, mesh: Option<usize>, frame: Option<&Frame>) {
        self.node_with(name, mesh, frame, None);
    }

    /// [`GlbBuilder::node`] with application data in the node's `extras` (what it stands for,
    /// for a viewer to list).
    pub(crate) fn node_with(&mut self, name: &str, mesh: Option<usize>, frame: Option<&Frame>, extras: Option<Value>) {
        let mut node = json!({ "name": name });
        if let Some(e) = extras {
            node["extras"] = e;
        }
        if let Some(m) = mesh {
            node["mesh"] = json!(m);
        }
        if let Some(f) = frame {
            let q = DQuat::from_mat3(&DMat3::from_cols(f.u, f.v, f.n)).normalize();
            node["rotation"] = json!(q.to_array());
            node["translation"] = json!(f.origin.to_array());
        }
        self.nodes.push(node);
    }

    /// Number of nodes so far, the root included.
    pub(crate) fn node_count(&self) -> usize {
        self.nodes.len() + 1
    }

    /// The GLB bytes: header, JSON chunk (space-padded), binary chunk (zero-padded).
    pub(crate) fn finish(self, root_name: &str) -> Result<Vec<u8>, SceneError> {
        let children: Vec<usize> = (1..=self.nodes.len()).collect();
        let mut root = json!({
            "name": root_name, "rotation": Z_UP_TO_Y_UP, "scale": [MM_TO_M, MM_TO_M, MM_TO_M],
        });
        if !children.is_empty() {
            root["children"] = json!(children);
        }
        let mut doc = json!({
            "asset": { "version": "2.0", "generator": crate::export::plan_json::generator() },
            "scene": 0,
            "scenes": [{ "nodes": [0] }],
            "nodes": std::iter::once(root).chain(self.nodes).collect::<Vec<_>>(),
        });
        for (key, list) in [
            ("meshes", self.meshes),
            ("materials", self.materials),
            ("accessors", self.accessors),
            ("bufferViews", self.views),
        ] {
            if !list.is_empty() {
                doc[key] = Value::Array(list);
            }
        }
        if !self.bin.is_empty() {
            doc["buffers"] = json!([{ "byteLength": self.bin.len() }]);
        }
        let json = serde_json::to_vec(&doc).map_err(|e| SceneError::Bug(e.to_string()))?;
        pack(json, self.bin)
    }
}

/// Whether `data` draws anything in `mode` (glTF forbids empty accessors).
fn drawable(data: &MeshData, mode: Mode) -> bool {
    !data.positions.is_empty() && data.indices.len() >= mode.per()
}

/// Packs the two chunks into a GLB container (glTF 2.0 spec, section 4.4).
fn pack(mut json: Vec<u8>, bin: Vec<u8>) -> Result<Vec<u8>, SceneError> {
    while !json.len().is_multiple_of(4) {
        json.push(b' ');
    }
    let bin_chunk = if bin.is_empty() { 0 } else { 8 + bin.len() };
    let total = 12 + 8 + json.len() + bin_chunk;
    let len32 = |n: usize| u32::try_from(n).map_err(|_| SceneError::TooLarge { what: "the GLB".into() });
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&len32(total)?.to_le_bytes());
    out.extend_from_slice(&len32(json.len())?.to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&json);
    if !bin.is_empty() {
        out.extend_from_slice(&len32(bin.len())?.to_le_bytes());
        out.extend_from_slice(b"BIN\0");
        out.extend_from_slice(&bin);
    }
    Ok(out)
}
