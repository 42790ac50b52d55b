//! The material a cross-section's loops enclose.

use platener_geom::polygon::{signed_area, total_area};
use platener_geom::{GridError, Polygon, Ring, boolean};

use super::SliceLoop;

/// The material a layer's loops enclose (also the plates step's mid-plane sections).
pub fn fill(loops: &[SliceLoop]) -> Result<Vec<Polygon>, GridError> {
    let mut components: Vec<u32> = loops.iter().map(|l| l.component).collect();
    components.sort_unstable();
    components.dedup();
    let rings_of = |c: u32| -> Vec<Ring> {
        loops
            .iter()
            .filter(|l| l.component == c)
            .map(|l| l.points.clone())
            .collect()
    };
    if components.len() <= 1 {
        let rings: Vec<Ring> = loops.iter().map(|l| l.points.clone()).collect();
        return boolean::from_rings_even_odd(&rings);
    }
    let mut solids = Vec::new();
    let mut negative = Vec::new();
    for c in components {
        let rings = rings_of(c);
        let turning: f64 = rings.iter().map(|r| signed_area(r)).sum();
        let polygons = boolean::from_rings_even_odd(&rings)?;
        if turning >= 0.0 {
            solids.extend(polygons);
        } else {
            negative.push(polygons);
        }
    }
    let solid_union = boolean::union_all(&solids)?;
    let mut cavities = Vec::new();
    for polygons in negative {
        let inside = total_area(&boolean::intersection(&polygons, &solid_union)?);
        // A clockwise body mostly inside the others is a cavity; one on its own is a body
        // whose open surface the mesh step could not orient reliably.
        if inside >= 0.5 * total_area(&polygons) {
            cavities.extend(polygons);
        } else {
            solids.extend(polygons);
        }
    }
    let union = boolean::union_all(&solids)?;
    if cavities.is_empty() {
        Ok(union)
    } else {
        boolean::difference(&union, &cavities)
    }
}
