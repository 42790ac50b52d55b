//! Every step's snapshot of a conversion as bounded JSON, for the web service's debug view.
//!
//! The debug view shows what each step made: its time, warnings, a 3D scene and the snapshot
//! as JSON. Snapshots can be large (a plate's outline of thousands of vertices, tens of
//! thousands of planar groups), so the JSON is *bounded*: any array longer than
//! [`ARRAY_LIMIT`] keeps its first elements and says how many there were. What a person
//! debugging needs whole — plate ids, the shape pairs each plate came from, overlap and
//! containment counts, connections with their joint kinds, part ids — is in a separate
//! `summary` that is never shortened below [`LIST_LIMIT`] entries. Like `inspect`, this
//! module only reads a finished [`State`]; it runs nothing.

use serde::Serialize;
use serde_json::{Value, json};

use crate::context::Warning;
use crate::pipeline::{State, StepId};
use crate::plan::PlanInput;
use crate::scene::View;

/// Arrays in a snapshot longer than this are summarised.
pub const ARRAY_LIMIT: usize = 24;
/// The summary's lists (plates, connections, parts) keep at most this many entries.
pub const LIST_LIMIT: usize = 5000;

/// One step of a conversion as the debug view shows it.
#[derive(Debug, Clone, Serialize)]
pub struct StepDebug {
    /// The step's name.
    pub step: &'static str,
    /// The step that ran before it (whose output is its input); `None` for `read`.
    pub input: Option<&'static str>,
    /// Wall time in milliseconds.
    pub millis: f64,
    /// Its warnings.
    pub warnings: Vec<Warning>,
    /// The scene that draws its output: its own view, else the nearest earlier step's
    /// (cleanup and weld show the model, joints the plates, the cutting plan the parts).
    pub view: Option<&'static str>,
    /// Whether `view` draws this step's own snapshot.
    pub view_exact: bool,
    /// Ids and relations, whole: plates with their shape pairs, connections with joint kinds,
    /// parts and joints, counts of what the bounded snapshot shortens.
    pub summary: Value,
    /// The snapshot, arrays longer than [`ARRAY_LIMIT`] summarised.
    pub snapshot: Value,
}

/// The debug form of every step `state` ran, in order.
pub fn steps(state: &State) -> Vec<StepDebug> {
    let mut out: Vec<StepDebug> = Vec::new();
    let mut last_view = None;
    for record in &state.records {
        let Some(step) = StepId::ALL.into_iter().find(|s| s.name() == record.name) else {
            continue;
        };
        let own = view_of(step);
        last_view = own.or(last_view);
        out.push(StepDebug {
            step: record.name,
            input: out.last().map(|s| s.step),
            millis: record.millis,
            warnings: record.warnings.clone(),
            view: last_view.map(View::name),
            view_exact: own.is_some(),
            summary: summary(state, step),
            snapshot: snapshot(state, step).map_or(Value::Null, |v| bounded(v, ARRAY_LIMIT)),
        });
    }
    out
}

/// The scene that draws `step`'s own snapshot, if there is one.
pub fn view_of(step: StepId) -> Option<View> {
    match step {
        StepId::Read => Some(View::Model),
        StepId::Mesh => Some(View::Wireframe),
        StepId::Coplanar => Some(View::Coplanar),
        StepId::Classify => Some(View::Primitives),
        StepId::Plates => Some(View::Plates),
        StepId::Bends => Some(View::Bent),
        StepId::Parts | StepId::Stacked | StepId::Relief | StepId::Layers => Some(View::Final),
        _ => None,
    }
}

/// `value` with every array longer than `limit` replaced by
/// `{"count": n, "first": [its first limit / 2 elements]}`, recursively.
pub fn bounded(value: Value, limit: usize) -> Value {
    match value {
        Value::Array(items) if items.len() > limit => {
            let count = items.len();
            let first: Vec<Value> = items.into_iter().take(limit / 2).map(|v| bounded(v, limit)).collect();
            json!({"count": count, "first": first})
        }
        Value::Array(items) => Value::Array(items.into_iter().map(|v| bounded(v, limit)).collect()),
        Value::Object(map) => Value::Object(map.into_iter().map(|(k, v)| (k, bounded(v, limit))).collect()),
        v => v,
    }
}

/// The snapshot `step` stored, as JSON (before bounding).
fn snapshot(state: &State, step: StepId) -> Option<Value> {
    fn to<T: Serialize>(s: Option<&std::sync::Arc<T>>) -> Option<Value> {
        s.and_then(|s| serde_json::to_value(s.as_ref()).ok())
    }
    match step {
        StepId::Read => to(state.read.as_ref()),
        StepId::Cleanup => to(state.cleanup.as_ref()),
        StepId::Weld => to(state.weld.as_ref()),
        StepId::Mesh => to(state.mesh.as_ref()),
        StepId::Coplanar => to(state.coplanar.as_ref()),
        StepId::Classify => to(state.classify.as_ref()),
        StepId::Shapes => to(state.shapes.as_ref()),
        StepId::Plates => to(state.plates.as_ref()),
        StepId::Bends => to(state.bends.as_ref()),
        StepId::Joints => to(state.joints.as_ref()),
        StepId::Stacked => to(state.stacked.as_ref()),
        StepId::Interlocked => to(state.interlocked.as_ref()),
        StepId::Relief => to(state.relief.as_ref()),
        StepId::Layers => to(state.layers.as_ref()),
        // The parts snapshot has no serde form: its summary lists it.
        StepId::Parts => None,
        StepId::Kerf => to(state.kerf.as_ref()),
        StepId::Labels => to(state.labels.as_ref()),
        StepId::Sheets => to(state.sheets.as_ref()),
        StepId::Export => to(state.export.as_ref()),
    }
}

/// What [`StepDebug::summary`] holds for `step`.
fn summary(state: &State, step: StepId) -> Value {
    match step {
        StepId::Read => state.read.as_ref().map_or(
            Value::Null,
            |m| json!({"triangles": m.triangles.len(), "solids": m.solids, "bounds": m.bounds}),
        ),
        StepId::Cleanup => state.cleanup.as_ref().map_or(Value::Null, |c| {
            json!({"triangles": c.triangles.len(), "degenerate_removed": c.degenerate_removed,
                   "duplicates_removed": c.duplicates_removed})
        }),
        StepId::Weld => state.weld.as_ref().map_or(
            Value::Null,
            |w| json!({"vertices": w.vertices.len(), "triangles": w.triangles.len(), "distance": w.distance}),
        ),
        StepId::Mesh => state.mesh.as_ref().map_or(
            Value::Null,
            |m| json!({"vertices": m.vertices.len(), "triangles": m.triangles.len(), "surface_area": m.surface_area}),
        ),
        StepId::Coplanar => state
            .coplanar
            .as_ref()
            .map_or(Value::Null, |g| json!({"groups": g.groups.len()})),
        StepId::Classify => state.classify.as_ref().map_or(Value::Null, |c| {
            json!({"primitives": c.primitives.len(), "volumes": c.volumes.len(),
                   "groups": state.coplanar.as_ref().map(|g| g.groups.len())})
        }),
        StepId::Shapes => state
            .shapes
            .as_ref()
            .map_or(Value::Null, |s| json!({"shapes": s.shapes.len()})),
        StepId::Plates => plates_summary(state),
        StepId::Bends => bends_summary(state),
        StepId::Joints => joints_summary(state),
        // Each step's own parts; `relief` and `layers` made none when they changed nothing.
        StepId::Parts => state.parts.as_deref().map_or(Value::Null, parts_summary),
        StepId::Stacked => state.stacked_parts.as_deref().map_or(Value::Null, parts_summary),
        StepId::Interlocked => state.interlocked_parts.as_deref().map_or(Value::Null, parts_summary),
        StepId::Relief => state.relief_parts.as_deref().map_or(Value::Null, parts_summary),
        StepId::Layers => state.layers_parts.as_deref().map_or(Value::Null, parts_summary),
        StepId::Kerf | StepId::Labels | StepId::Sheets | StepId::Export => cutting_summary(state),
    }
}

/// Plates (ids 1-based, as the plates scene's `plate-N` nodes) with the shapes each was made
/// from (an inherent plate's pair of opposite faces), and what overlap handling removed.
fn plates_summary(state: &State) -> Value {
    let Some(p) = state.plates.as_ref() else {
        return Value::Null;
    };
    let plates = listed(&p.plates, |i, plate| {
        json!({"id": i + 1, "kind": plate.kind, "thickness": plate.thickness,
               "area": plate.area, "shapes": plate.shapes})
    });
    let pairs = p
        .plates
        .iter()
        .filter(|plate| plate.kind == crate::plates::PlateKind::Inherent)
        .count();
    json!({
        "plates": plates,
        "count": p.plates.len(),
        "pairs": pairs,
        "contained_removed": p.contained_removed,
        "trimmed": p.trimmed,
        "rejoined": p.rejoined,
        "corners_closed": p.corners_closed,
        "features": p.features.len(),
        "overlaps": listed(&p.overlaps, |_, o| overlap_summary(&p.plates, o)),
    })
}

/// One resolved overlap with its plates as ids: those (1-based) made from the shapes it names.
/// A trimmed plate split in pieces has several; one later rejoined or grown has none.
fn overlap_summary(plates: &[crate::plates::Plate], o: &crate::plates::Overlap) -> Value {
    let ids = |shapes: &[u32]| -> Vec<usize> {
        let found = plates.iter().enumerate().filter(|(_, p)| p.shapes == shapes);
        found.map(|(i, _)| i + 1).collect()
    };
    json!({"trimmed": ids(&o.trimmed), "by": ids(&o.by), "trimmed_shapes": o.trimmed,
           "by_shapes": o.by, "area": o.area})
}

/// Connections between plates (ids 1-based) with their joint kind and finger style, and per
/// joint the plate that claimed its ends (the regions themselves are in the snapshot).
/// The bent parts: their plates (numbered as in the plates step), bends and seams, and the
/// candidates that stayed joints.
fn bends_summary(state: &State) -> Value {
    let Some(b) = state.bends.as_ref() else {
        return Value::Null;
    };
    let parts = listed(&b.parts, |_, p| {
        let plates: Vec<u32> = p.plates().iter().map(|plate| plate + 1).collect();
        json!({"plates": plates, "bends": p.bends.len(), "seams": p.seams.len(), "splits": p.splits.len()})
    });
    let refused = listed(
        &b.refused,
        |_, r| json!({"plates": [r.plates[0] + 1, r.plates[1] + 1], "reason": r.reason}),
    );
    json!({"style": b.style, "parts": parts, "count": b.parts.len(), "candidates": b.candidates, "refused": refused})
}

fn joints_summary(state: &State) -> Value {
    let Some(j) = state.joints.as_ref() else {
        return Value::Null;
    };
    let connections = listed(&j.connections, |_, c| {
        json!({"plates": [c.plates[0] + 1, c.plates[1] + 1], "kind": c.kind, "style": c.style,
               "angle_deg": c.angle_deg, "segments": c.segments, "label": c.label})
    });
    let claims = listed(
        &j.regions,
        |_, r| json!({"label": r.label, "plates": [r.plates[0] + 1, r.plates[1] + 1], "claimed_by": r.claimed_by + 1}),
    );
    // Which of the bends step's bent parts hold together once jointed (1-based, as listed
    // there), and why the others stay jointed plates.
    let held: Vec<usize> = j.held_bends.iter().map(|k| k + 1).collect();
    let refused = listed(
        &j.refused_bends,
        |_, r| json!({"plates": [r.plates[0] + 1, r.plates[1] + 1], "reason": r.reason}),
    );
    json!({"connections": connections, "count": j.connections.len(), "keys": j.keys.len(), "claims": claims,
           "bent_parts_held": held, "bent_parts_refused": refused})
}

/// Parts (ids as engraved and as the final scene's `part-ID` nodes) and their joints.
fn parts_summary(input: &PlanInput) -> Value {
    let parts = listed(&input.parts, |_, p| {
        json!({"id": p.id, "kind": p.kind, "thickness": p.thickness,
               "area": p.polygon.area(), "merged": p.merged})
    });
    let joints = listed(
        &input.joints,
        |_, j| json!({"parts": j.parts, "kind": j.kind, "angle_deg": j.angle_deg, "label": j.label}),
    );
    json!({"parts": parts, "joints": joints, "count": input.parts.len(), "glued": input.glued.len()})
}

/// The first [`LIST_LIMIT`] of `items` as JSON: a summary list stays whole for any model one
/// would debug, and bounded for the rest.
fn listed<T>(items: &[T], entry: impl Fn(usize, &T) -> Value) -> Vec<Value> {
    items
        .iter()
        .take(LIST_LIMIT)
        .enumerate()
        .map(|(i, t)| entry(i, t))
        .collect()
}

/// Counts of the cutting plan so far.
fn cutting_summary(state: &State) -> Value {
    json!({
        "parts": state.final_parts().as_ref().map(|p| p.parts.len()),
        "sheets": state.sheets.as_ref().map(|s| s.sheets.len()),
        "files": state.export.as_ref().map(|e| e.files.len()),
    })
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use super::*;
    use crate::convert::{Request, convert_all, no_progress};
    use crate::method::MethodKind;
    use crate::{Cancel, Settings, Source};
    use platener_fixtures::samples;

    fn box_state(method: MethodKind) -> State {
        state_of(&samples::closed_box(100.0, 80.0, 60.0, 3.0), method)
    }

    fn state_of(triangles: &[crate::read::Triangle], method: MethodKind) -> State {
        let bytes = samples::to_binary_stl(triangles, "box");
        let source = Source::Bytes {
            name: "box.stl".into(),
            bytes: Arc::from(bytes),
        };
        let request = Request {
            methods: vec![method],
            ..Request::new(source, Settings::default())
        };
        let all = convert_all(request, &Cancel::default(), no_progress());
        all.methods[0].state.clone().expect("the box converts")
    }

    #[test]
    fn a_box_has_six_plate_pairs_and_twelve_corner_joints() {
        let steps = steps(&box_state(MethodKind::Plate));
        let names: Vec<&str> = steps.iter().map(|s| s.step).collect();
        assert_eq!(
            names,
            StepId::of_method(MethodKind::Plate)
                .iter()
                .map(|s| s.name())
                .collect::<Vec<_>>()
        );
        assert_eq!(steps[0].input, None);
        assert_eq!(steps[1].input, Some("read"));
        let plates = steps.iter().find(|s| s.step == "plates").expect("plates");
        assert_eq!(plates.summary["count"], 6);
        assert_eq!(plates.summary["pairs"], 6);
        for p in plates.summary["plates"].as_array().expect("list") {
            assert_eq!(p["shapes"].as_array().map(Vec::len), Some(2), "{p}");
            assert_eq!(p["kind"], "inherent");
        }
        assert_eq!((plates.view, plates.view_exact), (Some("plates"), true));
        let joints = steps.iter().find(|s| s.step == "joints").expect("joints");
        assert_eq!(joints.summary["count"], 12);
        let connections = joints.summary["connections"].as_array().expect("list");
        assert!(
            connections
                .iter()
                .all(|c| c["kind"] == "corner" && c["style"] == "finger")
        );
        assert!(
            connections
                .iter()
                .flat_map(|c| c["plates"].as_array().into_iter().flatten())
                .all(|id| (1..=6).contains(&id.as_u64().unwrap_or(0)))
        );
        assert_eq!((joints.view, joints.view_exact), (Some("bent"), false));
        let parts = steps.iter().find(|s| s.step == "parts").expect("parts");
        assert_eq!(parts.summary["count"], 6);
        assert!(
            parts.summary["joints"]
                .as_array()
                .expect("joints")
                .iter()
                .all(|j| j["kind"] == "finger")
        );
    }

    /// The box's joint regions, straight from the joints snapshot (the debug JSON's source).
    #[test]
    fn a_box_has_twelve_joint_regions_inside_their_plates_each_claimed_by_one_of_its_plates() {
        let state = box_state(MethodKind::Plate);
        let joints = state.joints.as_ref().expect("joints");
        assert_eq!(joints.regions.len(), 12);
        for r in &joints.regions {
            assert!(r.plates.contains(&r.claimed_by), "{r:?}");
            for (side, region) in r.polygons.iter().enumerate() {
                let plate = r.plates[side] as usize;
                let area = region.area();
                assert!(area > 1.0, "joint {} on plate {plate}: area {area}", r.label);
                let outline = std::slice::from_ref(&joints.outlines[plate]);
                let (lo, hi) = joints.outlines[plate].bounds();
                let outside =
                    platener_geom::boolean::difference(std::slice::from_ref(region), outline).expect("difference");
                let inside = area - platener_geom::polygon::total_area(&outside);
                assert!(
                    inside > 0.3 * area,
                    "joint {} on plate {plate}: {inside} of {area} inside",
                    r.label
                );
                let (rlo, rhi) = region.bounds();
                assert!(
                    rlo.cmpge(lo - 1e-6).all() && rhi.cmple(hi + 1e-6).all(),
                    "joint {} on plate {plate}",
                    r.label
                );
            }
        }
        let steps = steps(&state);
        let summary = &steps.iter().find(|s| s.step == "joints").expect("joints").summary;
        let claims = summary["claims"].as_array().expect("claims");
        assert_eq!(claims.len(), 12);
        for c in claims {
            assert!(c["plates"].as_array().expect("pair").contains(&c["claimed_by"]), "{c}");
        }
        let snapshot = &steps.iter().find(|s| s.step == "joints").expect("joints").snapshot;
        assert_eq!(snapshot["regions"].as_array().map(Vec::len), Some(12));
        assert!(
            snapshot["regions"][0]["polygons"][1]["outer"].is_array(),
            "{}",
            snapshot["regions"][0]
        );
    }

    /// A solid block's six faces extruded inwards overlap along every edge: each trimmed plate
    /// lost area to a plate ranked above it, and the debug summary names both by plate ids.
    #[test]
    fn a_solid_block_lists_the_overlaps_trimming_resolved_with_both_plates() {
        let block = samples::cuboid(glam::DVec3::ZERO, glam::DVec3::new(60.0, 40.0, 30.0));
        let state = state_of(&block, MethodKind::Plate);
        let plates = state.plates.as_ref().expect("plates");
        let lost: Vec<&crate::plates::Overlap> = plates.overlaps.iter().filter(|o| o.area > 1.0).collect();
        assert!(plates.trimmed > 0);
        assert!(
            lost.len() >= plates.trimmed,
            "{} overlaps, {} trimmed",
            lost.len(),
            plates.trimmed
        );
        for o in &lost {
            assert_ne!(o.trimmed, o.by);
            let claimed = platener_geom::polygon::total_area(&o.claimed);
            assert!(claimed >= o.area - 1e-6, "{claimed} < {}", o.area);
        }
        let steps = steps(&state);
        let summary = &steps.iter().find(|s| s.step == "plates").expect("plates").summary;
        let listed = summary["overlaps"].as_array().expect("overlaps");
        assert_eq!(listed.len(), plates.overlaps.len());
        for o in listed.iter().filter(|o| o["area"].as_f64().is_some_and(|a| a > 1.0)) {
            for side in ["trimmed", "by"] {
                let ids = o[side].as_array().expect("ids");
                assert_eq!(ids.len(), 1, "{o}");
                assert!((1..=6).contains(&ids[0].as_u64().unwrap_or(0)), "{o}");
            }
            assert_ne!(o["trimmed"], o["by"]);
        }
    }

    #[test]
    fn the_test_set_has_unique_url_names_and_closed_models() {
        let set = platener_fixtures::test_set::test_set();
        let mut names: Vec<&str> = set.iter().map(|m| m.name).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), set.len());
        for m in &set {
            assert!(m.name.chars().all(|c| c.is_ascii_lowercase() || c == '-'), "{}", m.name);
            assert!(m.triangles.len() >= 12, "{}", m.name);
        }
    }

    /// The test set's textured box exercises the classifier: its 12 walls (6 textured, 6 of
    /// the cavity) are planes, and the primitives view draws the classify step.
    #[test]
    fn the_test_sets_textured_box_is_twelve_planes_in_the_primitives_view() {
        let model = platener_fixtures::test_set::test_set()
            .into_iter()
            .find(|m| m.name == "textured-box")
            .expect("in the set");
        let state = state_of(&model.triangles, MethodKind::Classifier);
        let c = state.classify.as_ref().expect("classified");
        let kinds: Vec<_> = c.primitives.iter().map(|p| p.shape.kind()).collect();
        assert_eq!(kinds, [crate::classify::SurfaceKind::Plane; 12]);
        let steps = steps(&state);
        let classify = steps.iter().find(|s| s.step == "classify").expect("classify");
        assert_eq!((classify.view, classify.view_exact), (Some("primitives"), true));
        assert_eq!(classify.summary["primitives"], 12);
        let scene = state.scene(View::Primitives).expect("drawn");
        assert!(scene.nodes >= 13 && scene.points > 0, "{} nodes", scene.nodes);
    }

    #[test]
    fn long_arrays_are_summarised_and_short_ones_kept() {
        let v = json!({"a": (0..100).collect::<Vec<_>>(), "b": [[1, 2], [3, 4]]});
        let b = bounded(v, 10);
        assert_eq!(b["a"]["count"], 100);
        assert_eq!(b["a"]["first"], json!([0, 1, 2, 3, 4]));
        assert_eq!(b["b"], json!([[1, 2], [3, 4]]));
        let steps = steps(&box_state(MethodKind::Stacked));
        let stacked = steps.iter().find(|s| s.step == "stacked").expect("stacked");
        assert!(
            stacked.summary["count"].as_u64().is_some_and(|n| n > 0),
            "{}",
            stacked.summary
        );
        let text = serde_json::to_string(&steps).expect("json");
        assert!(text.len() < 2_000_000, "{} bytes", text.len());
    }
}
