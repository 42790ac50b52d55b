//! The stacked method's must-hold rules (issue 7), checked on what it writes: plan.json's parts
//! with their outlines, holes and transforms, and its joints.
//!
//! Tolerances: slots and shafts "do not intersect" when the region of one part's outline whose
//! columns meet the other's volume is under [`TOUCH_AREA`] (the 1 µm grid of the booleans along
//! the slot's edges); areas of slots against shafts agree within [`SLOT_TOL`] relative. Volumes
//! are integrated over [`LEVELS`] sub-planes per part against a 360-gon disc (area error under
//! 0.01 %); the surface is sampled at [`SURFACE_SAMPLES`] evenly spread points.

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::OnceLock;

use platener::convert;
use platener::glam::{DVec2, DVec3};
use platener::method::MethodKind;
use platener::pipeline::StepId;

type Conversion = platener::State;
use platener::plan::{JointKind, PartKind, Plan, PlanPart};
use platener::settings::StackAxis;
use platener::{Cancel, Settings, Source};
use platener_fixtures::samples;
use platener_geom::polygon::total_area;
use platener_geom::slab::Slab;
use platener_geom::{Frame, Polygon, boolean};

/// Columns of two parts meeting over less than this (mm²) do not intersect.
const TOUCH_AREA: f64 = 1e-2;
/// Relative tolerance of slot areas against the shafts through them.
const SLOT_TOL: f64 = 1e-3;
/// What a layer may lose beyond its slots (mm²): the outline repair cuts thin wedges under the
/// kerf away (`platener_geom::clean`, 0.097 mm² on an organic corpus layer), never adds.
const REPAIR_TOL: f64 = 0.15;
/// Sub-planes per part for volume integrals.
const LEVELS: usize = 6;
/// Points sampled on a sphere's surface.
const SURFACE_SAMPLES: usize = 2000;

/// Settings for tests: one nesting try, so a debug build nests 40 parts in seconds.
fn quick(axis: StackAxis) -> Settings {
    let mut s = Settings::default();
    s.cut.nest_tries = 1;
    s.cut.fine_rotations = false;
    s.stacked.axis = axis;
    s
}

fn run(name: &str, triangles: Vec<[DVec3; 3]>, settings: Settings) -> Conversion {
    let source = Source::triangles(name, triangles);
    convert(MethodKind::Stacked, source, settings, &Cancel::default()).expect("converts")
}

/// The 100 mm sphere, converted once for all tests that look at it.
fn sphere() -> &'static Conversion {
    static SPHERE: OnceLock<Conversion> = OnceLock::new();
    SPHERE.get_or_init(|| {
        run(
            "sphere",
            samples::sphere(DVec3::ZERO, 50.0, 96, 48),
            quick(StackAxis::Auto),
        )
    })
}

fn plan(c: &Conversion) -> &Plan {
    &c.bundle().expect("exported").plan
}

fn frame(p: &PlanPart) -> Frame {
    let m = p.transform;
    let col = |j: usize| DVec3::new(m[0][j], m[1][j], m[2][j]);
    Frame {
        u: col(0),
        v: col(1),
        n: col(2),
        origin: col(3),
    }
}

fn polygon(p: &PlanPart) -> Polygon {
    Polygon {
        outer: p.outline.clone(),
        holes: p.holes.clone(),
    }
}

fn slab(p: &PlanPart) -> Slab {
    Slab {
        frame: frame(p),
        polygon: polygon(p),
        thickness: p.thickness,
    }
}

/// Groups of parts connected through joints.
fn assemblies(plan: &Plan) -> Vec<Vec<u32>> {
    let mut root: BTreeMap<u32, u32> = plan.parts.iter().map(|p| (p.id, p.id)).collect();
    fn find(root: &mut BTreeMap<u32, u32>, a: u32) -> u32 {
        let r = root[&a];
        if r == a {
            a
        } else {
            let top = find(root, r);
            root.insert(a, top);
            top
        }
    }
    for j in &plan.joints {
        let (a, b) = (find(&mut root, j.parts[0]), find(&mut root, j.parts[1]));
        root.insert(a.max(b), a.min(b));
    }
    let mut groups: BTreeMap<u32, Vec<u32>> = BTreeMap::new();
    let ids: Vec<u32> = root.keys().copied().collect();
    for id in ids {
        let r = find(&mut root, id);
        groups.entry(r).or_default().push(id);
    }
    groups.into_values().collect()
}

fn disc(center: DVec2, radius: f64) -> Polygon {
    Polygon::new(
        (0..360)
            .map(|i| center + DVec2::from_angle((i as f64).to_radians()) * radius)
            .collect(),
    )
}

/// (volume of the parts inside the ball, volume of the parts), mm³.
fn volume_inside_ball(plan: &Plan, center: DVec3, radius: f64) -> (f64, f64) {
    let (mut inside, mut total) = (0.0, 0.0);
    for p in &plan.parts {
        let (f, poly) = (frame(p), polygon(p));
        total += poly.area() * p.thickness;
        let dz = p.thickness / LEVELS as f64;
        for i in 0..LEVELS {
            let z = (i as f64 + 0.5) * dz;
            let local = f.to_local(center);
            let r2 = radius * radius - (local.z - z).powi(2);
            if r2 <= 0.0 {
                continue;
            }
            let cut =
                boolean::intersection(std::slice::from_ref(&poly), &[disc(local.truncate(), r2.sqrt())]).expect("grid");
            inside += total_area(&cut) * dz;
        }
    }
    (inside, total)
}

/// Share of evenly spread points of the sphere's surface within `reach` of some part.
fn surface_covered(plan: &Plan, center: DVec3, radius: f64, reach: f64) -> f64 {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    let slabs: Vec<Slab> = plan.parts.iter().map(slab).collect();
    let covered = (0..SURFACE_SAMPLES)
        .filter(|&i| {
            let z = 1.0 - 2.0 * (i as f64 + 0.5) / SURFACE_SAMPLES as f64;
            let r = (1.0 - z * z).sqrt();
            let a = golden * i as f64;
            let q = center + radius * DVec3::new(r * a.cos(), r * a.sin(), z);
            slabs.iter().any(|s| s.within(q, reach))
        })
        .count();
    covered as f64 / SURFACE_SAMPLES as f64
}

/// Every shaft joint: the layer as cut does not meet the shaft's volume, the shaft passes
/// through the layer (its columns meet the uncut layer's slab over a full band), and what each
/// layer lost to its slots is the shafts' sections through it, plus at most the pinches opened
/// beside their ends.
fn assert_slots_match(c: &Conversion) {
    let plan = plan(c);
    let stack = c.stacked.as_ref().expect("stack");
    let outlines: BTreeMap<u32, &Polygon> = stack
        .layers
        .iter()
        .flat_map(|l| &l.islands)
        .map(|i| (i.part, &i.outline))
        .collect();
    let parts: BTreeMap<u32, &PlanPart> = plan.parts.iter().map(|p| (p.id, p)).collect();
    // (the shafts' sections, the most opened pinches may add) per layer, mm².
    let mut slot_area: BTreeMap<u32, (f64, f64)> = BTreeMap::new();
    let bridge = Settings::default().stacked.margin / 2.0;
    for j in &plan.joints {
        assert_eq!(j.kind, JointKind::Shaft);
        let (shaft, layer) = (parts[&j.parts[0]], parts[&j.parts[1]]);
        assert_eq!((layer.kind, shaft.kind), (PartKind::Layer, PartKind::Shaft));
        let (ls, ss) = (slab(layer), slab(shaft));
        let overlap = total_area(&ls.columns_meeting(&ss, 1e-3).expect("grid"));
        assert!(
            overlap < TOUCH_AREA,
            "layer {} meets shaft {}: {overlap} mm²",
            layer.id,
            shaft.id
        );
        // The shaft's band inside the uncut layer, seen from the shaft: as tall as the layer.
        let uncut = Slab {
            polygon: outlines[&layer.id].clone(),
            ..ls
        };
        let band = total_area(&ss.columns_meeting(&uncut, 1e-6).expect("grid"));
        let width = band / layer.thickness;
        assert!(
            width > 1.0,
            "shaft {} does not pass through layer {}",
            shaft.id,
            layer.id
        );
        let entry = slot_area.entry(layer.id).or_default();
        entry.0 += width * shaft.thickness;
        // A notch that would pinch the layer opens through material under a bridge wide
        // beside the slot's ends: at most a bridge by the shaft's thickness at each end.
        entry.1 += 2.0 * bridge * shaft.thickness;
    }
    // A layer too thin for its number beside its slot (a peg's) carries it on a tab, which adds
    // at most the tab's size (tabs.rs), less what the slot keeps clear.
    let numbers = c
        .final_parts()
        .as_ref()
        .and_then(|p| p.method_report.clone())
        .expect("a report");
    let on_tab: Vec<u64> = numbers["numbers"]["on_tab"]
        .as_array()
        .expect("a list")
        .iter()
        .filter_map(|v| v.as_u64())
        .collect();
    let kerf = plan.settings.cut.kerf.expect("recorded");
    for (id, (want, pinches)) in slot_area {
        let lost = outlines[&id].area() - polygon(parts[&id]).area();
        let tab = if on_tab.contains(&u64::from(id)) {
            let size = platener::stacked::tab_size(id, kerf);
            (size.x + 0.5) * size.y
        } else {
            0.0
        };
        assert!(
            lost + tab >= want - SLOT_TOL * want && lost <= want + pinches + SLOT_TOL * want + REPAIR_TOL,
            "layer {id}: slots {lost} mm², shafts {want} mm²"
        );
    }
}

/// Every pair of islands in adjacent layers that overlap is joined through a common shaft.
fn assert_neighbours_joined(c: &Conversion) {
    let stack = c.stacked.as_ref().expect("stack");
    assert!(stack.unjoined.is_empty(), "{:?}", stack.unjoined);
    for w in stack.layers.windows(2) {
        for a in &w[0].islands {
            for b in &w[1].islands {
                let overlap = total_area(
                    &boolean::intersection(std::slice::from_ref(&a.outline), std::slice::from_ref(&b.outline))
                        .expect("grid"),
                );
                if overlap <= 0.01 {
                    continue;
                }
                let joined = stack.shafts.iter().any(|s| {
                    s.bands.windows(2).any(|p| {
                        let (x, y) = (
                            &stack.layers[p[0].layer].islands[p[0].island],
                            &stack.layers[p[1].layer].islands[p[1].island],
                        );
                        (x.part, y.part) == (a.part, b.part)
                    })
                });
                assert!(
                    joined,
                    "layers {} and {}: parts {} and {} overlap by {overlap} mm² unjoined",
                    w[0].number, w[1].number, a.part, b.part
                );
            }
        }
    }
}

#[test]
fn a_100_mm_sphere_makes_33_or_34_layers_in_one_assembly() {
    let c = sphere();
    let plan = plan(c);
    let layers: Vec<&PlanPart> = plan.parts.iter().filter(|p| p.kind == PartKind::Layer).collect();
    let shafts = plan.parts.len() - layers.len();
    eprintln!("sphere: {} layers, {shafts} shafts", layers.len());
    assert!((33..=34).contains(&layers.len()), "{} layers", layers.len());
    assert!(shafts >= 1);
    assert_eq!(assemblies(plan).len(), 1, "one connected assembly");
    assert_eq!(plan.method, platener::plan::Method::Stacked);
    // Layers are one thickness apart along z, bottom first, each at its height.
    let mut heights: Vec<f64> = layers.iter().map(|p| p.transform[2][3]).collect();
    heights.sort_by(f64::total_cmp);
    for w in heights.windows(2) {
        assert!((w[1] - w[0] - 3.0).abs() < 1e-9, "{heights:?}");
    }
    // The stack is centred on the sphere: 33 × 3 mm from −49.5 mm.
    assert!((heights[0] + 49.5).abs() < 1e-3, "{}", heights[0]);
}

#[test]
fn sphere_parts_lie_inside_it_and_cover_its_surface() {
    let plan = plan(sphere());
    let (inside, total) = volume_inside_ball(plan, DVec3::ZERO, 50.0);
    let covered = surface_covered(plan, DVec3::ZERO, 50.0, 3.0);
    eprintln!(
        "sphere: parts {total:.0} mm³ (sphere {:.0}), {:.1} % inside; surface within 3 mm: {:.1} %",
        4.0 / 3.0 * std::f64::consts::PI * 50f64.powi(3),
        100.0 * inside / total,
        100.0 * covered
    );
    assert!(inside >= 0.9 * total, "{inside} of {total}");
    assert!(covered >= 0.9, "{covered}");
}

#[test]
fn sphere_shafts_fill_their_slots_exactly() {
    assert_slots_match(sphere());
}

#[test]
fn layer_outlines_lie_on_the_surface_at_their_mid_plane() {
    // Outline vertices are where mesh edges cross the mid-plane: on the inscribed facets,
    // between the sphere's radius and that times cos(π / 48) (the facets' sag).
    let plan = plan(sphere());
    let sag = (std::f64::consts::PI / 48.0).cos();
    for p in plan.parts.iter().filter(|p| p.kind == PartKind::Layer) {
        let f = frame(p);
        for v in &p.outline {
            let r = f.to_model(DVec3::new(v.x, v.y, p.thickness / 2.0)).length();
            assert!(r <= 50.0 + 1e-3 && r >= 50.0 * sag * sag - 1e-3, "part {}: {r}", p.id);
        }
    }
}

#[test]
fn shafts_never_bridge_a_layer_they_do_not_pass_through() {
    let c = sphere();
    let stack = c.stacked.as_ref().expect("stack");
    let plan = plan(c);
    for s in &stack.shafts {
        let layers: Vec<usize> = s.bands.iter().map(|b| b.layer).collect();
        let want: Vec<usize> = (layers[0]..=layers[layers.len() - 1]).collect();
        assert_eq!(layers, want, "consecutive");
        // The shaft's outline spans exactly those layers' heights.
        let part = plan.parts.iter().find(|p| p.id == s.part).expect("in plan.json");
        let (lo, hi) = polygon(part).bounds();
        let t = stack.layer_thickness();
        assert!((lo.y - t * layers[0] as f64).abs() < 1e-9);
        assert!((hi.y - t * (layers[layers.len() - 1] + 1) as f64).abs() < 1e-9);
        assert!(s.bands.len() >= 2, "phase 3");
    }
}

#[test]
fn a_standing_torus_has_two_islands_in_the_middle_and_all_are_joined() {
    let tris = samples::torus(DVec3::ZERO, DVec3::Y, 40.0, 15.0, 96, 32);
    let c = run("torus", tris, quick(StackAxis::Auto));
    let stack = c.stacked.as_ref().expect("stack");
    let counts: Vec<usize> = stack.layers.iter().map(|l| l.islands.len()).collect();
    eprintln!("torus: islands per layer {counts:?}, {} shafts", stack.shafts.len());
    assert_eq!(counts.len(), 37);
    assert_eq!((counts[0], counts[counts.len() - 1]), (1, 1));
    // |z| < 25 mm − margin of the tube's curve: two islands.
    let middle = &counts[10..27];
    assert!(middle.iter().all(|&n| n == 2), "{counts:?}");
    assert_neighbours_joined(&c);
    assert_eq!(assemblies(plan(&c)).len(), 1);
    assert_slots_match(&c);
    assert_verified(&c);
    assert_outlines_valid(&c);
}

#[test]
fn two_separate_bodies_are_each_joined_to_their_neighbours() {
    let c = run("two bodies", samples::two_bodies(20.0), quick(StackAxis::Auto));
    let stack = c.stacked.as_ref().expect("stack");
    let counts: Vec<usize> = stack.layers.iter().map(|l| l.islands.len()).collect();
    eprintln!(
        "two bodies: islands per layer {counts:?}, {} shafts",
        stack.shafts.len()
    );
    assert!(counts.contains(&2));
    // The flat torus' layers are rings: islands with a hole.
    assert!(
        stack
            .layers
            .iter()
            .flat_map(|l| &l.islands)
            .any(|i| !i.outline.holes.is_empty())
    );
    assert_neighbours_joined(&c);
    assert_eq!(assemblies(plan(&c)).len(), 2, "one assembly per body");
    assert_slots_match(&c);
    assert_verified(&c);
    assert_outlines_valid(&c);
}

#[test]
fn the_output_is_the_same_every_time() {
    let tris = samples::sphere(DVec3::new(3.0, -2.0, 1.0), 20.0, 40, 20);
    let a = run("small sphere", tris.clone(), quick(StackAxis::X));
    let b = run("small sphere", tris, quick(StackAxis::X));
    assert_eq!(a.bundle().expect("zip").zip, b.bundle().expect("zip").zip);
    // Sliced along x: the layers' normal is +x.
    let p = &plan(&a).parts[0];
    assert_eq!(
        (p.transform[0][2], p.transform[1][2], p.transform[2][2]),
        (1.0, 0.0, 0.0)
    );
}

/// The corpus' organic models, or `None` after saying why this test skips (CI fails instead).
fn corpus_organic() -> Option<PathBuf> {
    platener_fixtures::samples::shared_corpus()
        .map(|d| d.join("organic"))
        .map_err(|m| eprintln!("{m}"))
        .ok()
}

#[test]
fn organic_corpus_models_convert() {
    let Some(dir) = corpus_organic() else {
        return;
    };
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("readable")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "stl"))
        .collect();
    files.sort();
    assert!(!files.is_empty());
    for file in files {
        let name = file.file_name().expect("name").to_string_lossy().to_string();
        // As given: converts, or (a model a few mm or less across, in unknown units) says that
        // nothing is large enough to cut and how to fix it.
        match convert(
            MethodKind::Stacked,
            Source::File(file.clone()),
            quick(StackAxis::Auto),
            &Cancel::default(),
        ) {
            Ok(c) => {
                eprintln!("{name} as given: {} parts", plan(&c).parts.len());
                assert!(!plan(&c).parts.is_empty(), "{name}");
            }
            Err(e) => {
                eprintln!("{name} as given: {e}");
                assert!(e.to_string().contains("`scale`"), "{name}: {e}");
            }
        }
        // At 100 mm across, as a user would convert it with --scale: converts, and every pair
        // of islands the method could not join is reported.
        let mut probe = platener::State::new(Source::File(file.clone()), Settings::default());
        platener::pipeline::run(&[StepId::Read], &mut probe, &Cancel::default()).expect("reads");
        let b = probe.read.as_ref().expect("read").bounds;
        let extent = (b.max - b.min).max_element();
        let settings = Settings {
            scale: 100.0 / extent,
            ..quick(StackAxis::Auto)
        };
        let c = convert(MethodKind::Stacked, Source::File(file), settings, &Cancel::default())
            .unwrap_or_else(|e| panic!("{name} at 100 mm: {e}"));
        let stack = c.stacked.as_ref().expect("stack");
        let islands: usize = stack.layers.iter().map(|l| l.islands.len()).sum();
        let plan = plan(&c);
        eprintln!(
            "{name} at 100 mm: {} layers, {islands} islands, {} shafts, {} dropped, {} unjoined, {} assemblies, loops {:?}",
            stack.layers.iter().filter(|l| !l.islands.is_empty()).count(),
            stack.shafts.len(),
            stack.dropped.len(),
            stack.unjoined.len(),
            assemblies(plan).len(),
            stack.loops
        );
        assert_slots_match(&c);
    }
}

/// `platener verify` against the model: no interference, no more groups than solids, at least
/// 90 % of the surface within its cover distance of a part and 90 % of the parts' volume inside.
fn assert_verified(c: &Conversion) -> platener::verify::Verification {
    let mesh = c.mesh.as_ref().expect("mesh");
    let v = platener::verify::verify(plan(c), Some(mesh));
    eprintln!(
        "verify {}: {} parts, interference {:.4} %, {} group(s), surface covered {:?}, volume inside {:?}",
        plan(c).source.name,
        v.parts,
        100.0 * v.interference_share,
        v.groups,
        v.surface_covered,
        v.volume_inside
    );
    assert!(v.passed(), "{:?}", v.problems);
    assert!(v.surface_covered.expect("with the model") >= 0.9);
    assert!(v.volume_inside.expect("with the model") >= 0.9);
    v
}

/// Every part's outline is valid at the plan's kerf (no touch, no crossing, nothing narrower
/// than the kerf), as made: no repair was refused. A shaft's notch that would pinch its layer
/// is opened to the outside or shortened where the shaft is placed (`stacked::notch`).
fn assert_outlines_valid(c: &Conversion) {
    let plan = plan(c);
    let kerf = plan.settings.cut.kerf();
    for p in &plan.parts {
        let findings = platener_geom::validate(&polygon(p), kerf);
        assert!(findings.is_empty(), "part {}: {findings:?}", p.id);
    }
    let refused: Vec<String> = c
        .warnings()
        .filter(|w| w.message.contains("left as it is"))
        .map(|w| w.message.clone())
        .collect();
    assert!(refused.is_empty(), "{refused:?}");
}

#[test]
fn the_sphere_passes_platener_verify() {
    assert_eq!(assert_verified(sphere()).groups, 1);
}
