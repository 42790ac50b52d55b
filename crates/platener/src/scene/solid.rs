//! The views of solids: `plates`, `bent` and `final`. Each plate or part is its polygon
//! extruded over its thickness in its own frame, and its node's transform (rotation and
//! translation of the frame, exactly plan.json's `transform`) places it in the model.

use glam::DVec3;
use platener_geom::{Frame, Polygon};

use super::extrude::{extrude, slab_mesh};
use super::glb::{GlbBuilder, MeshData, Mode};
use super::palette::Colour;
use super::{Scene, SceneError};
use crate::bends::Bends;
use crate::plan::Part;
use crate::plates::Plates;

/// The `plates` view: one node `plate-N` (N from 1, in the snapshot's order) per plate, each
/// a closed slab in its own colour.
pub fn plates(plates: &Plates) -> Result<Scene, SceneError> {
    let mut glb = GlbBuilder::default();
    for (i, p) in plates.plates.iter().enumerate() {
        let name = format!("plate-{}", i + 1);
        solid(&mut glb, &name, &p.polygon, p.thickness, &p.frame, Colour::nth(i))?;
    }
    Scene::finish(glb, "plates", Vec::new())
}

/// The `bent` view: one node `plate-N` per plate, as in `plates`, coloured by the bent part
/// it belongs to (every plate of one bent part in one colour); plates that stay flat parts
/// take the colours after them.
pub fn bent(plates_snapshot: &Plates, bends: Option<&Bends>) -> Result<Scene, SceneError> {
    let mut glb = GlbBuilder::default();
    let bent_parts = bends.map_or(0, |b| b.parts.len());
    let mut flat = bent_parts;
    for (i, p) in plates_snapshot.plates.iter().enumerate() {
        let colour = match bends.and_then(|b| b.member_of(i)) {
            Some((k, _)) => k,
            None => {
                flat += 1;
                flat - 1
            }
        };
        let name = format!("plate-{}", i + 1);
        solid(&mut glb, &name, &p.polygon, p.thickness, &p.frame, Colour::nth(colour))?;
    }
    let note = match bends {
        None => "bent parts were not computed (the bends step did not run)".to_string(),
        Some(b) if b.style.is_none() => "bending is off (`bend` none): every plate is its own part".to_string(),
        Some(b) => format!(
            "{} bent part(s) from {} plates; each bent part in one colour",
            b.parts.len(),
            b.parts.iter().map(|p| p.members.len()).sum::<usize>()
        ),
    };
    Scene::finish(glb, "bent", vec![note])
}

/// The `final` view, also the plan's `assembly.glb`: one node `part-ID` per part (ascending
/// id), its nominal polygon (joints, slots and holes included) extruded from local z = 0 to
/// its thickness and placed by its frame; colours by id. A bent part's node holds its pieces
/// ([`Part::pieces`]: the segments flat, the bend zones' slices forming the curved strip),
/// each a closed solid, in the part's frame.
pub fn assembly(parts: &[Part]) -> Result<Scene, SceneError> {
    Assembly::new(parts)?.scene()
}

/// The assembled parts as solids: what the `final` view and `assembly.glb` are written from,
/// and what the gallery's thumbnail draws ([`crate::export::thumbnail`]), so the two never
/// show different things.
#[derive(Debug, Clone)]
pub struct Assembly {
    solids: Vec<PartSolid>,
}

/// One part's solid in its own frame.
#[derive(Debug, Clone)]
struct PartSolid {
    id: u32,
    name: String,
    data: MeshData,
    frame: Frame,
    colour: Colour,
}

impl Assembly {
    /// Every part extruded (a bent part bent), in ascending id order.
    pub fn new(parts: &[Part]) -> Result<Self, SceneError> {
        let mut order: Vec<&Part> = parts.iter().collect();
        order.sort_by_key(|p| p.id);
        let solids = order
            .into_iter()
            .map(|p| {
                let id = p.id;
                let name = format!("part-{}", p.id);
                let data = if p.segments.is_empty() {
                    slab_mesh(&p.polygon, p.thickness)
                } else {
                    bent_mesh(p)
                }
                .map_err(|e| e.about(&name))?;
                let colour = Colour::nth(p.id.saturating_sub(1) as usize);
                Ok(PartSolid {
                    id,
                    name,
                    data,
                    frame: p.frame,
                    colour,
                })
            })
            .collect::<Result<_, SceneError>>()?;
        Ok(Assembly { solids })
    }

    /// The `final` scene ([`assembly`]).
    pub fn scene(&self) -> Result<Scene, SceneError> {
        let mut glb = GlbBuilder::default();
        for s in &self.solids {
            let mesh = glb.mesh(&s.name, &s.data, Mode::Triangles, s.colour, false)?;
            glb.node(&s.name, mesh, Some(&s.frame));
        }
        Scene::finish(glb, "assembly", Vec::new())
    }

    /// Every triangle in the model's coordinates (mm, Z up), counter-clockwise seen from
    /// outside, with its part's colour (sRGB): parts in ascending id order.
    pub fn triangles(&self) -> impl Iterator<Item = ([DVec3; 3], [u8; 3])> + '_ {
        self.part_triangles().map(|(_, t, colour)| (t, colour))
    }

    /// [`Assembly::triangles`] with each one's part id, for drawings of some parts only (the
    /// assembly instructions' steps).
    pub fn part_triangles(&self) -> impl Iterator<Item = (u32, [DVec3; 3], [u8; 3])> + '_ {
        self.solids.iter().flat_map(|s| {
            s.data.indices.chunks_exact(3).map(move |t| {
                let corner = |i: u32| s.frame.to_model(s.data.positions[i as usize]);
                (s.id, [corner(t[0]), corner(t[1]), corner(t[2])], s.colour.srgb())
            })
        })
    }
}

/// A bent part's pieces extruded and carried into the part's own frame (the node's transform
/// is the part's frame, as for every part).
fn bent_mesh(part: &Part) -> Result<MeshData, SceneError> {
    let pieces = part.pieces().map_err(|e| SceneError::Bends(e.to_string()))?;
    let mut data = MeshData::default();
    for piece in &pieces {
        let (positions, triangles) = extrude(&piece.polygon, piece.thickness)?;
        let base = u32::try_from(data.positions.len()).map_err(|_| SceneError::TooLarge { what: "a part".into() })?;
        data.positions
            .extend(positions.iter().map(|q| part.frame.to_local(piece.frame.to_model(*q))));
        data.indices.extend(triangles.into_iter().flatten().map(|i| i + base));
    }
    Ok(data)
}

/// Adds one slab node; a polygon with no area gets a node without a mesh.
fn solid(
    glb: &mut GlbBuilder,
    name: &str,
    polygon: &Polygon,
    thickness: f64,
    frame: &Frame,
    colour: Colour,
) -> Result<(), SceneError> {
    let data = slab_mesh(polygon, thickness).map_err(|e| e.about(name))?;
    let mesh = glb.mesh(name, &data, Mode::Triangles, colour, false)?;
    glb.node(name, mesh, Some(frame));
    Ok(())
}
