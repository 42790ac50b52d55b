//! Loading a scene back with the `gltf` crate and measuring it as geometry.

use std::collections::BTreeMap;

use glam::{DMat4, DQuat, DVec3, Mat4};

/// One child of the root: its name, transform (local → model mm), mesh (its one line or
/// triangle primitive) and the points of a POINTS primitive beside it (the primitives view).
pub struct Node {
    pub name: String,
    pub matrix: DMat4,
    pub mode: Option<gltf::mesh::Mode>,
    pub positions: Vec<DVec3>,
    pub indices: Vec<u32>,
    pub points: Vec<DVec3>,
}

impl Node {
    /// Positions after the node's transform (model coordinates, mm).
    pub fn world(&self) -> Vec<DVec3> {
        self.positions
            .iter()
            .map(|p| self.matrix.transform_point3(*p))
            .collect()
    }

    /// Triangles as index triples (solid meshes).
    pub fn triangles(&self) -> Vec<[u32; 3]> {
        self.indices.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect()
    }
}

/// A loaded scene: the root's scale and rotation, its children.
pub struct Loaded {
    pub root_scale: [f32; 3],
    pub root_rotation: [f32; 4],
    pub nodes: Vec<Node>,
}

/// Parses the GLB (the gltf crate validates the JSON) and reads every child's mesh.
pub fn load(glb: &[u8]) -> Loaded {
    let g = gltf::Gltf::from_slice(glb).expect("a valid GLB");
    let blob = g.blob.clone().unwrap_or_default();
    let scene = g.default_scene().expect("a default scene");
    let roots: Vec<gltf::Node> = scene.nodes().collect();
    assert_eq!(roots.len(), 1, "a single root node");
    let (t, rotation, scale) = roots[0].transform().decomposed();
    assert_eq!(t, [0.0; 3], "the root is not moved");
    let nodes = roots[0]
        .children()
        .map(|n| {
            let matrix = Mat4::from_cols_array_2d(&n.transform().matrix()).as_dmat4();
            let (mut mode, mut positions, mut indices, mut points) = (None, Vec::new(), Vec::new(), Vec::new());
            for p in n.mesh().iter().flat_map(|m| m.primitives()) {
                let r = p.reader(|_| Some(&blob[..]));
                let at: Vec<DVec3> = r
                    .read_positions()
                    .expect("positions")
                    .map(|p| DVec3::from(p.map(f64::from)))
                    .collect();
                if p.mode() == gltf::mesh::Mode::Points {
                    assert!(
                        r.read_indices().is_none() && points.is_empty(),
                        "one unindexed POINTS primitive"
                    );
                    points = at;
                    continue;
                }
                assert!(mode.is_none(), "one line or triangle primitive per mesh");
                mode = Some(p.mode());
                positions = at;
                indices = r.read_indices().expect("indices").into_u32().collect();
            }
            Node {
                name: n.name().unwrap_or_default().to_string(),
                matrix,
                mode,
                positions,
                indices,
                points,
            }
        })
        .collect();
    Loaded {
        root_scale: scale,
        root_rotation: rotation,
        nodes,
    }
}

/// Asserts the root carries the mm → m scale and the Z-up → Y-up turn (-90° about x).
pub fn assert_root(l: &Loaded) {
    assert_eq!(l.root_scale, [0.001; 3]);
    let q = DQuat::from_array(l.root_rotation.map(f64::from));
    let up = q * DVec3::Z;
    assert!((up - DVec3::Y).length() < 1e-6, "model +z maps to {up}, not +y");
    assert!((q * DVec3::Y - -DVec3::Z).length() < 1e-6);
}

/// Watertight: every edge (by vertex index) is used by exactly two triangles, once in each
/// direction, and by position too every edge is used as often in each direction (no cracks
/// between coincident vertices; where an outline touches itself each side has its own copy of
/// the point, so the mesh stays manifold by index).
pub fn watertight(positions: &[DVec3], triangles: &[[u32; 3]]) -> Result<(), String> {
    let mut id: BTreeMap<[u64; 3], usize> = BTreeMap::new();
    let key: Vec<usize> = positions
        .iter()
        .map(|p| {
            let next = id.len();
            *id.entry(p.to_array().map(f64::to_bits)).or_insert(next)
        })
        .collect();
    let mut by_index: BTreeMap<(u32, u32), usize> = BTreeMap::new();
    let mut by_position: BTreeMap<(usize, usize), usize> = BTreeMap::new();
    for t in triangles {
        for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
            *by_index.entry((a, b)).or_default() += 1;
            *by_position.entry((key[a as usize], key[b as usize])).or_default() += 1;
        }
    }
    for (&(a, b), &n) in &by_index {
        let back = by_index.get(&(b, a)).copied().unwrap_or(0);
        if n != 1 || back != 1 {
            let (p, q) = (positions[a as usize], positions[b as usize]);
            return Err(format!("edge {p} → {q} used {n} times, back {back} times"));
        }
    }
    for (&(a, b), &n) in &by_position {
        if by_position.get(&(b, a)).copied().unwrap_or(0) != n {
            return Err(format!("a crack along an edge between positions {a} and {b}"));
        }
    }
    Ok(())
}

/// Signed volume (sum of tetrahedra to the first vertex): positive when the mesh faces out.
pub fn volume(positions: &[DVec3], triangles: &[[u32; 3]]) -> f64 {
    let o = positions.first().copied().unwrap_or_default();
    triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| positions[i as usize] - o);
            a.dot(b.cross(c)) / 6.0
        })
        .sum()
}

/// Axis-aligned bounds of points.
pub fn bounds(points: impl IntoIterator<Item = DVec3>) -> (DVec3, DVec3) {
    points.into_iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(p), hi.max(p)),
    )
}
