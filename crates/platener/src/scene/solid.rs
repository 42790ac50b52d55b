//! The views of solids: `plates`, `bent` and `final`. Each plate or part is its polygon
//! extruded over its thickness in its own frame, and its node's transform (rotation and
//! translation of the frame, exactly plan.json's `transform`) places it in the model.

use platener_geom::{Frame, Polygon};

use super::extrude::slab_mesh;
use super::glb::{GlbBuilder, Mode};
use super::palette::Colour;
use super::{Scene, SceneError};
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

/// The `bent` view: plates coloured by the bent part they belong to. No method merges plates
/// into bent parts yet, so each plate is its own part and the view equals `plates`.
pub fn bent(plates_snapshot: &Plates) -> Result<Scene, SceneError> {
    let mut scene = plates(plates_snapshot)?;
    scene.notes.push("no bent parts yet: each plate is its own part".into());
    Ok(scene)
}

/// The `final` view, also the plan's `assembly.glb`: one node `part-ID` per part (ascending
/// id), its nominal polygon (joints, slots and holes included) extruded from local z = 0 to
/// its thickness and placed by its frame; colours by id.
pub fn assembly(parts: &[Part]) -> Result<Scene, SceneError> {
    let mut order: Vec<&Part> = parts.iter().collect();
    order.sort_by_key(|p| p.id);
    let mut glb = GlbBuilder::default();
    for p in order {
        let colour = Colour::nth(p.id.saturating_sub(1) as usize);
        solid(
            &mut glb,
            &format!("part-{}", p.id),
            &p.polygon,
            p.thickness,
            &p.frame,
            colour,
        )?;
    }
    Scene::finish(glb, "assembly", Vec::new())
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
