//! 3MF reader on the `threemf` crate: expands the build (items → objects → components) into one
//! triangle soup in millimetres.
//!
//! A 3MF file can place one object several times and build objects out of other objects, each
//! with its own transform and in any of six units; the rest of platener only wants triangles in
//! mm, so all of that is resolved here, with limits so a hostile file cannot loop or explode.

use std::collections::HashMap;
use std::fs::File;
use std::io::BufReader;
use std::path::Path;

use glam::{DAffine3, DVec3};
use threemf::model::{Mesh, Model, Object, Unit};

use super::{RawMesh, ReadErrorKind, Triangle};

/// Deepest nesting of components followed; real files use two or three levels.
const MAX_DEPTH: usize = 32;
/// Most object instances (build items plus components) expanded, against exponential blow-up.
const MAX_INSTANCES: usize = 1_000_000;
/// Most triangles produced (about 1.4 GB of corners).
const MAX_TRIANGLES: usize = 20_000_000;

/// Reads every object of the 3MF build with its transform.
///
/// Each build item's object is expanded recursively through its components, composing the
/// transforms, and the result is converted from the model's unit to millimetres. `solids` is the
/// number of build items. Triangle and item numbers in messages count from 0.
pub fn read_path(path: &Path) -> Result<RawMesh, ReadErrorKind> {
    let file = File::open(path).map_err(|e| ReadErrorKind::Io(e.to_string()))?;
    let size = file.metadata().map_err(|e| ReadErrorKind::Io(e.to_string()))?.len();
    if size == 0 {
        return Err(ReadErrorKind::Empty);
    }
    let parts = threemf::read(BufReader::new(file)).map_err(describe_error)?;
    Package::new(&parts)?.expand()
}

/// Reads a 3MF held in memory (uploads), as [`read_path`] reads a file.
pub fn parse_bytes(bytes: &[u8]) -> Result<RawMesh, ReadErrorKind> {
    if bytes.is_empty() {
        return Err(ReadErrorKind::Empty);
    }
    let parts = threemf::read(std::io::Cursor::new(bytes)).map_err(describe_error)?;
    Package::new(&parts)?.expand()
}

/// Turns a `threemf` error into a message saying what to do.
fn describe_error(error: threemf::Error) -> ReadErrorKind {
    ReadErrorKind::ThreeMf(match error {
        threemf::Error::Zip(e) => format!(
            "not a readable ZIP archive ({e}); a 3MF file is a ZIP, so this one is damaged or \
             not a 3MF: download or export it again"
        ),
        threemf::Error::Io(e) => format!(
            "the archive could not be unpacked ({e}); the file is damaged: download or export \
             it again"
        ),
        threemf::Error::XMLDe(e) => format!(
            "the 3D model XML could not be read ({e}); the file is damaged or uses a layout \
             platener cannot read: open it in a slicer and export it again as 3MF or STL"
        ),
        other => other.to_string(),
    })
}

/// Millimetres per model unit, and the unit's name.
fn unit_scale(unit: &Unit) -> (f64, &'static str) {
    match unit {
        Unit::Micron => (0.001, "micron"),
        Unit::Millimeter => (1.0, "millimeter"),
        Unit::Centimeter => (10.0, "centimeter"),
        Unit::Inch => (25.4, "inch"),
        Unit::Foot => (304.8, "foot"),
        Unit::Meter => (1000.0, "meter"),
    }
}

/// The model parts of the archive, with the root (the part holding the build) picked out.
struct Package<'a> {
    /// Every `*.model` part, in archive order.
    parts: &'a [Model],
    /// Index of the part whose build is printed.
    root: usize,
    /// Per part: object id → object.
    objects: Vec<HashMap<usize, &'a Object>>,
}

impl<'a> Package<'a> {
    /// Indexes the objects of every part and finds the root part.
    fn new(parts: &'a [Model]) -> Result<Self, ReadErrorKind> {
        if parts.is_empty() {
            return Err(ReadErrorKind::ThreeMf(
                "the archive holds no 3D model (no `.model` part such as 3D/3dmodel.model); it is \
                 damaged or not a 3MF file: export it again"
                    .into(),
            ));
        }
        // `threemf` reads every `*.model` part without saying which one `_rels/.rels` names as
        // the root; the root is the one with build items (extra parts of the Production extension
        // have an empty build).
        let with_build: Vec<usize> = (0..parts.len())
            .filter(|&p| parts.get(p).is_some_and(|m| !m.build.item.is_empty()))
            .collect();
        let root = match with_build.as_slice() {
            [] | [_] => with_build.first().copied().unwrap_or(0),
            several => {
                return Err(ReadErrorKind::ThreeMf(format!(
                    "the archive holds {} model parts that each list build items; platener cannot \
                     tell which one is printed: open the file in a slicer and export it as a \
                     single-part 3MF or as STL",
                    several.len()
                )));
            }
        };
        let mut objects = Vec::with_capacity(parts.len());
        for part in parts {
            let mut by_id = HashMap::with_capacity(part.resources.object.len());
            for object in &part.resources.object {
                if by_id.insert(object.id, object).is_some() {
                    return Err(ReadErrorKind::ThreeMf(format!(
                        "two objects have the id {}; ids must be unique: the file is damaged, \
                         export it again",
                        object.id
                    )));
                }
            }
            objects.push(by_id);
        }
        Ok(Package { parts, root, objects })
    }

    /// Finds object `id` as referenced from `part` (by `referrer`, for messages).
    ///
    /// Objects in the root part may refer to objects in other parts (Production extension,
    /// `p:path`); `threemf` drops the path, so such references are matched by id, and only when
    /// exactly one part could be meant. `cross_part` is set when that happened.
    fn resolve(
        &self,
        part: usize,
        id: usize,
        referrer: &str,
        cross_part: &mut bool,
    ) -> Result<(usize, &'a Object), ReadErrorKind> {
        let local = self.objects.get(part).and_then(|m| m.get(&id).copied());
        if part != self.root {
            // Non-root parts may only refer to their own objects.
            return local.map(|o| (part, o)).ok_or_else(|| missing(referrer, id));
        }
        let elsewhere: Vec<(usize, &'a Object)> = self
            .objects
            .iter()
            .enumerate()
            .filter(|&(p, _)| p != part)
            .filter_map(|(p, m)| m.get(&id).map(|o| (p, *o)))
            .collect();
        match (local, elsewhere.as_slice()) {
            (Some(object), []) => Ok((part, object)),
            (None, [(p, object)]) => {
                *cross_part = true;
                Ok((*p, *object))
            }
            (None, []) => Err(missing(referrer, id)),
            _ => Err(ReadErrorKind::ThreeMf(format!(
                "{referrer} refers to object {id}, which is defined in several model parts of the \
                 archive (3MF Production extension); platener cannot tell which one is meant: \
                 open the file in a slicer and export it as a plain 3MF or as STL"
            ))),
        }
    }

    /// Expands the whole build into millimetre triangles.
    fn expand(&self) -> Result<RawMesh, ReadErrorKind> {
        let root = self
            .parts
            .get(self.root)
            .ok_or_else(|| ReadErrorKind::ThreeMf("the archive holds no 3D model part".into()))?;
        let (scale, unit_name) = unit_scale(&root.unit);
        let mut expander = Expander {
            package: self,
            scale,
            triangles: Vec::new(),
            instances: 0,
            mirrored: 0,
            cross_part: false,
            stack: Vec::new(),
        };
        let mut notes = Vec::new();
        let items = &root.build.item;
        for (number, item) in items.iter().enumerate() {
            let referrer = format!("build item {number}");
            let transform = affine(item.transform.as_ref(), &referrer)?;
            let (part, object) = self.resolve(self.root, item.objectid, &referrer, &mut expander.cross_part)?;
            let before = expander.triangles.len();
            expander.expand(part, object, transform, &referrer)?;
            if expander.triangles.len() == before {
                notes.push(format!("{referrer} ({}) holds no triangles", object_label(object)));
            }
        }

        if items.is_empty() {
            notes.push("the build lists no items, so the file places nothing to print".into());
        }
        if scale != 1.0 {
            notes.push(format!(
                "model unit is {unit_name}; coordinates were converted to millimetres (x {scale})"
            ));
        }
        if expander.cross_part {
            notes.push(
                "components refer to objects in other model parts (3MF Production extension, as \
                 written by e.g. Bambu Studio); they were matched by object id"
                    .into(),
            );
            let other_unit = self
                .parts
                .iter()
                .map(|part| unit_scale(&part.unit))
                .find(|&(other, _)| other != scale);
            if let Some((_, other_name)) = other_unit {
                notes.push(format!(
                    "a secondary model part declares unit {other_name}; the main part's unit \
                     {unit_name} was used for everything"
                ));
            }
        }
        if expander.mirrored > 0 {
            notes.push(format!(
                "{} object placements mirror their object (transform with negative determinant); \
                 their triangles were re-wound so normals still point outwards",
                expander.mirrored
            ));
        }
        Ok(RawMesh {
            triangles: expander.triangles,
            solids: items.len(),
            notes,
            ..RawMesh::default()
        })
    }
}

/// The error for a reference to an object id that no part defines.
fn missing(referrer: &str, id: usize) -> ReadErrorKind {
    ReadErrorKind::ThreeMf(format!(
        "{referrer} refers to object {id}, which the model does not define; the file is damaged: \
         export it again"
    ))
}

/// `object 3` or `object 3 ("Bracket")`, for messages.
fn object_label(object: &Object) -> String {
    match &object.name {
        Some(name) if !name.is_empty() => format!("object {} ({name:?})", object.id),
        _ => format!("object {}", object.id),
    }
}

/// The first coordinate of `point` that is not finite.
fn non_finite(point: DVec3) -> Option<f64> {
    point.to_array().into_iter().find(|c| !c.is_finite())
}

/// A 3MF transform attribute as an affine map.
///
/// 3MF stores `m00 m01 m02 m10 m11 m12 m20 m21 m22 m30 m31 m32` for row vectors,
/// `p' = [x y z 1] · M`: each row `m_i0 m_i1 m_i2` is the image of axis `i` and the last row is
/// the translation, which is exactly glam's column-major `[x_axis, y_axis, z_axis, translation]`.
fn affine(transform: Option<&[f64; 12]>, owner: &str) -> Result<DAffine3, ReadErrorKind> {
    let Some(m) = transform else {
        return Ok(DAffine3::IDENTITY);
    };
    if let Some(bad) = m.iter().find(|v| !v.is_finite()) {
        return Err(ReadErrorKind::NonFinite {
            location: format!("{owner}, transform"),
            value: bad.to_string(),
        });
    }
    Ok(DAffine3::from_cols_array(m))
}

/// State of the build expansion.
struct Expander<'p, 'a> {
    /// The parts and their object indices.
    package: &'p Package<'a>,
    /// Millimetres per model unit.
    scale: f64,
    /// Output, in millimetres.
    triangles: Vec<Triangle>,
    /// Object instances expanded so far (limit [`MAX_INSTANCES`]).
    instances: usize,
    /// Instances placed with a mirroring transform.
    mirrored: usize,
    /// Whether a reference was resolved into another model part.
    cross_part: bool,
    /// The (part, object id) chain being expanded, for cycle detection.
    stack: Vec<(usize, usize)>,
}

impl Expander<'_, '_> {
    /// Emits `object` (from `part`) placed by `transform` (model units), then its components.
    fn expand(&mut self, part: usize, object: &Object, transform: DAffine3, item: &str) -> Result<(), ReadErrorKind> {
        let key = (part, object.id);
        if let Some(start) = self.stack.iter().position(|k| *k == key) {
            let chain: Vec<String> = self.stack[start..]
                .iter()
                .chain(std::iter::once(&key))
                .map(|(_, id)| id.to_string())
                .collect();
            return Err(ReadErrorKind::ThreeMf(format!(
                "{item}: objects contain each other in a cycle (object {}); the file is damaged: \
                 export it again",
                chain.join(" → object ")
            )));
        }
        if self.stack.len() >= MAX_DEPTH {
            return Err(ReadErrorKind::ThreeMf(format!(
                "{item}: components are nested more than {MAX_DEPTH} levels deep; flatten the \
                 model in a slicer or CAD program and export it again"
            )));
        }
        self.instances += 1;
        if self.instances > MAX_INSTANCES {
            return Err(ReadErrorKind::ThreeMf(format!(
                "the build expands to more than {MAX_INSTANCES} object placements; the file is \
                 damaged or hostile"
            )));
        }

        self.stack.push(key);
        if let Some(mesh) = &object.mesh {
            self.emit_mesh(object, mesh, transform, item)?;
        }
        if let Some(components) = &object.components {
            for (number, component) in components.component.iter().enumerate() {
                let referrer = format!("{item}: {}, component {number}", object_label(object));
                let local = affine(component.transform.as_ref(), &referrer)?;
                let (child_part, child) =
                    self.package
                        .resolve(part, component.objectid, &referrer, &mut self.cross_part)?;
                // Row vectors: p · C · T, i.e. the component's transform first.
                self.expand(child_part, child, transform * local, item)?;
            }
        }
        self.stack.pop();
        Ok(())
    }

    /// Emits the triangles of one mesh placed by `transform`, in millimetres.
    fn emit_mesh(
        &mut self,
        object: &Object,
        mesh: &Mesh,
        transform: DAffine3,
        item: &str,
    ) -> Result<(), ReadErrorKind> {
        let vertices = &mesh.vertices.vertex;
        let triangles = &mesh.triangles.triangle;
        let label = object_label(object);
        if self.triangles.len().saturating_add(triangles.len()) > MAX_TRIANGLES {
            return Err(ReadErrorKind::ThreeMf(format!(
                "the build expands to more than {MAX_TRIANGLES} triangles; simplify the model \
                 (decimate it) and export it again"
            )));
        }
        // A mirroring placement turns the object inside out; swapping two corners keeps the
        // winding's normal pointing outwards.
        let mirrored = transform.matrix3.determinant() < 0.0;
        if mirrored {
            self.mirrored += 1;
        }
        self.triangles.reserve(triangles.len());
        for (t, triangle) in triangles.iter().enumerate() {
            let mut corners: Triangle = [DVec3::ZERO; 3];
            for (slot, index) in corners.iter_mut().zip([triangle.v1, triangle.v2, triangle.v3]) {
                let vertex = vertices.get(index).ok_or_else(|| {
                    ReadErrorKind::ThreeMf(format!(
                        "{label}, triangle {t}: vertex index {index} is out of range (the object \
                         has {} vert{}, numbered from 0); the file is damaged: export it again",
                        vertices.len(),
                        if vertices.len() == 1 { "ex" } else { "ices" }
                    ))
                })?;
                let local = DVec3::new(vertex.x, vertex.y, vertex.z);
                if let Some(bad) = non_finite(local) {
                    return Err(ReadErrorKind::NonFinite {
                        location: format!("{label}, triangle {t}"),
                        value: bad.to_string(),
                    });
                }
                let placed = transform.transform_point3(local) * self.scale;
                if let Some(bad) = non_finite(placed) {
                    return Err(ReadErrorKind::NonFinite {
                        location: format!("{item}: {label}, triangle {t} after its transform"),
                        value: bad.to_string(),
                    });
                }
                *slot = placed;
            }
            if mirrored {
                corners.swap(1, 2);
            }
            self.triangles.push(corners);
        }
        Ok(())
    }
}
