//! The classifier method (issue 20) on the samples the plate method cannot read: a hollow box
//! whose walls carry a texture becomes its six walls with finger joints, a knurled cylinder a
//! bent wrap with two discs; each plan rebuilds its model (verify with the model).

use glam::{DQuat, DVec2, DVec3};
use platener::classify::SurfaceKind;
use platener::convert::{Request, convert, convert_all};
use platener::method::MethodKind;
use platener::plan::{JointKind, MarkKind, PartKind, Plan};
use platener::read::Triangle;
use platener::verify::{Verification, verify};
use platener::{Cancel, Settings, Source, State};
use platener_fixtures::samples;

fn convert_with(method: MethodKind, model: Vec<Triangle>) -> State {
    let settings = Settings {
        thicknesses: vec![3.0],
        ..Settings::default()
    };
    convert(method, Source::triangles("m", model), settings, &Cancel::default()).expect("converts")
}

fn checked(state: &State) -> (Plan, Verification) {
    let plan = state.export.as_ref().expect("exported").plan.clone();
    let v = verify(&plan, state.mesh.as_deref());
    (plan, v)
}

/// Asserts the plan rebuilds its model: no problem, ≥ 95 % of the parts' volume inside it,
/// ≥ 90 % of its surface covered, no interference.
fn rebuilds(v: &Verification) {
    assert!(v.passed(), "{:?}", v.problems);
    let inside = v.volume_inside.expect("measured");
    let covered = v.surface_covered.expect("measured");
    assert!(inside >= 0.95, "volume inside {inside}");
    assert!(covered >= 0.90, "surface covered {covered}");
    assert!(v.interference_share < 0.01, "interference {}", v.interference_share);
}

/// The unit normal of a part's plane in the model (its transform's third column).
fn normal_of(plan: &Plan, id: u32) -> DVec3 {
    let part = plan.parts.iter().find(|p| p.id == id).expect("part");
    let t = part.transform;
    DVec3::new(t[0][2], t[1][2], t[2][2]).normalize()
}

const SIZE: DVec3 = DVec3::new(120.0, 90.0, 70.0);

fn textured_box() -> Vec<Triangle> {
    samples::textured_box(SIZE, 3.0, 0.5, 10.0)
}

/// Six parts, one per wall, their normals along `axes` (the box's axes, moved), every wall
/// finger-jointed to its four neighbours.
fn assert_six_jointed_walls(plan: &Plan, axes: [DVec3; 3]) {
    assert_eq!(plan.parts.len(), 6);
    assert!(plan.parts.iter().all(|p| p.kind == PartKind::Plate));
    let mut per_axis = [0; 3];
    for part in &plan.parts {
        let n = normal_of(plan, part.id);
        let k = (0..3)
            .find(|&k| n.dot(axes[k]).abs() > 0.5f64.to_radians().cos())
            .unwrap_or_else(|| panic!("part {} normal {n} is along no axis of the box", part.id));
        per_axis[k] += 1;
    }
    assert_eq!(per_axis, [2, 2, 2]);
    // The box has 12 edges; each joins two walls.
    let fingers: Vec<[u32; 2]> = plan
        .joints
        .iter()
        .filter(|j| j.kind == JointKind::Finger)
        .map(|j| j.parts)
        .collect();
    assert_eq!(fingers.len(), 12, "{:?}", plan.joints);
    for part in &plan.parts {
        let meets = fingers.iter().filter(|j| j.contains(&part.id)).count();
        assert_eq!(meets, 4, "part {}", part.id);
    }
}

#[test]
fn a_textured_hollow_box_becomes_its_six_walls_with_finger_joints() {
    let state = convert_with(MethodKind::Classifier, textured_box());
    let (plan, v) = checked(&state);
    rebuilds(&v);
    assert_six_jointed_walls(&plan, [DVec3::X, DVec3::Y, DVec3::Z]);
    // The parts hold the walls' volume: the box less its cavity (the bumps add 1/4 of their
    // height on average, 0.125 mm over the outer faces).
    let walls = SIZE.element_product() - (SIZE - DVec3::splat(6.0)).element_product();
    let area: f64 = state
        .final_parts()
        .as_ref()
        .expect("parts")
        .parts
        .iter()
        .map(|p| p.polygon.area())
        .sum();
    let ratio = area * 3.0 / walls;
    assert!((ratio - 1.0).abs() < 0.03, "parts hold {ratio} of the walls' volume");
    let found = state.classify.as_ref().expect("classified");
    assert_eq!(found.primitives.len(), 12, "six outer and six inner walls");
}

/// The texture flattened onto each wall comes back as score marks on that wall's outer face:
/// one ring per bump (the surface standing out of the fitted plane), 12 × 9 on a 120 × 90
/// wall, 12 × 7 and 9 × 7 on the others.
#[test]
fn the_texture_is_engraved_on_the_walls_it_was_on() {
    let state = convert_with(MethodKind::Classifier, textured_box());
    let relief = state.relief.as_ref().expect("the relief step ran");
    let mut bumps: Vec<usize> = relief.textures.iter().map(|t| t.regions).collect();
    bumps.sort_unstable();
    assert_eq!(bumps, [63, 63, 84, 84, 108, 108]);
    let parts = &state.final_parts().as_ref().expect("parts").parts;
    for t in &relief.textures {
        // Bumps 0.5 mm high over a plane at their mean height (an eighth of the bump's square
        // of sines, about 0.125 mm): they stand out up to about 0.375 mm.
        assert!(t.amplitude > 0.3 && t.amplitude < 0.45, "{}", t.amplitude);
        // Each region is about the middle half of its 10 mm cell.
        let each = t.area / t.regions as f64;
        assert!(each > 15.0 && each < 40.0, "{each} mm² per bump");
        let part = parts.iter().find(|p| p.id == t.part).expect("the wall");
        let scores: Vec<_> = part.marks.iter().filter(|m| m.kind == MarkKind::Score).collect();
        assert_eq!(scores.len(), t.regions);
        assert!(scores.iter().all(|m| m.side == Some(t.side)));
        // Every mark lies on the part.
        let outline = &part.polygon;
        assert!(
            scores
                .iter()
                .flat_map(|m| &m.path)
                .all(|p| outline.contains(*p) || outline.boundary_distance_squared(*p) < 1e-6)
        );
    }
    // With --features ignore nothing is engraved.
    let settings = Settings {
        thicknesses: vec![3.0],
        features: platener::Features::Ignore,
        ..Settings::default()
    };
    let plain = convert(
        MethodKind::Classifier,
        Source::triangles("m", textured_box()),
        settings,
        &Cancel::default(),
    );
    let plain = plain.expect("converts");
    assert!(plain.relief.as_ref().expect("ran").textures.is_empty());
    let parts = &plain.final_parts().as_ref().expect("parts").parts;
    assert!(parts.iter().flat_map(|p| &p.marks).all(|m| m.kind != MarkKind::Score));
}

#[test]
fn the_plate_method_cannot_read_the_texture_the_classifier_can() {
    let plate = convert_with(MethodKind::Plate, textured_box());
    let groups = plate.coplanar.as_ref().expect("grouped").groups.len();
    assert!(groups > 1_000, "the texture splits the walls into {groups} groups");
    let (_, v) = checked(&plate);
    let inside = v.volume_inside.expect("measured");
    let classified = convert_with(MethodKind::Classifier, textured_box());
    assert_eq!(classified.coplanar.as_ref().expect("grouped").groups.len(), 12);
    let (_, w) = checked(&classified);
    assert!(
        w.volume_inside.expect("measured") > inside + 0.2,
        "{inside} → {:?}",
        w.volume_inside
    );
}

/// `--method all` on the textured box: the plate method's plan reproduces the surface as the
/// classifier's does, but a third of its volume stands proud of the walls; the score's `fit`
/// (issue 32) counts that, so the classifier's plan scores higher and is named best.
#[test]
fn the_classifier_is_named_best_on_the_textured_box() {
    let settings = Settings {
        thicknesses: vec![3.0],
        ..Settings::default()
    };
    let request = Request {
        methods: vec![MethodKind::Plate, MethodKind::Classifier],
        ..Request::new(Source::triangles("textured box", textured_box()), settings)
    };
    let all = convert_all(request, &Cancel::default(), platener::convert::no_progress());
    let [plate, classifier] = &all.methods[..] else {
        panic!("two methods")
    };
    let total = |m: &platener::convert::MethodResult| m.score.as_ref().expect("scored").total;
    let inside =
        |m: &platener::convert::MethodResult| m.verification.as_ref().and_then(|v| v.volume_inside).expect("measured");
    let fit = |m: &platener::convert::MethodResult| m.score.as_ref().expect("scored").quality.fit;
    assert!(
        fit(plate) < 0.95 && fit(classifier) > 0.99,
        "{} {}",
        fit(plate),
        fit(classifier)
    );
    assert!(total(classifier) > total(plate) + platener::convert::SCORE_TIE);
    assert!(
        inside(classifier) > inside(plate) + 0.2,
        "{} {}",
        inside(classifier),
        inside(plate)
    );
    assert_eq!(all.best, Some(MethodKind::Classifier));
}

#[test]
fn a_moved_textured_box_converts_the_same() {
    let mut rng = platener_geom::rng::SplitMix64::new(20);
    for _ in 0..2 {
        let axis = DVec3::new(rng.unit() - 0.5, rng.unit() - 0.5, rng.unit() - 0.5).normalize();
        let turn = DQuat::from_axis_angle(axis, rng.unit() * std::f64::consts::TAU);
        let shift = DVec3::new(rng.unit(), rng.unit(), rng.unit()) * 200.0;
        let moved = textured_box()
            .into_iter()
            .map(|t| t.map(|p| turn * p + shift))
            .collect();
        let state = convert_with(MethodKind::Classifier, moved);
        let (plan, v) = checked(&state);
        rebuilds(&v);
        assert_six_jointed_walls(&plan, [turn * DVec3::X, turn * DVec3::Y, turn * DVec3::Z]);
    }
}

#[test]
fn a_knurled_cylinder_becomes_a_bent_wrap_with_two_discs() {
    let (radius, height) = (50.0, 60.0);
    let state = convert_with(
        MethodKind::Classifier,
        samples::knurled_cylinder(radius, height, 0.5, 36),
    );
    let (plan, v) = checked(&state);
    rebuilds(&v);
    assert_eq!(
        plan.parts.len(),
        3,
        "{:?}",
        plan.parts.iter().map(|p| p.kind).collect::<Vec<_>>()
    );
    let wrap = plan
        .parts
        .iter()
        .find(|p| p.kind == PartKind::Bent)
        .expect("a bent wrap");
    let facets = wrap.segments.len();
    assert!(facets >= 8, "{facets} facets");
    assert_eq!(wrap.bends.len(), facets - 1, "one seam, every other facet edge bent");
    let discs: Vec<_> = plan.parts.iter().filter(|p| p.kind == PartKind::Plate).collect();
    assert_eq!(discs.len(), 2);
    for disc in discs {
        assert!(normal_of(&plan, disc.id).z.abs() > 0.5f64.to_radians().cos());
    }
    // The wrap is as long as the wall's mid-circle, less what the seam's fingers take: its
    // flat length lies between 95 % and 105 % of 2π(r − t/2).
    let xs = wrap.outline.iter().map(|p| p.x);
    let (lo, hi) = xs.fold((f64::MAX, f64::MIN), |(lo, hi), x| (lo.min(x), hi.max(x)));
    let ys = wrap.outline.iter().map(|p| p.y);
    let (blo, bhi) = ys.fold((f64::MAX, f64::MIN), |(lo, hi), y| (lo.min(y), hi.max(y)));
    let length = (hi - lo).max(bhi - blo);
    let mid = std::f64::consts::TAU * (radius - 1.5);
    assert!((length / mid - 1.0).abs() < 0.05, "flat length {length} for {mid}");
}

#[test]
fn a_clean_box_converts_as_the_plate_method_converts_it() {
    let model = samples::closed_box(120.0, 90.0, 70.0, 3.0);
    let (plate, _) = checked(&convert_with(MethodKind::Plate, model.clone()));
    // Beside the plate method, the classifier sees the exact faces and skips, saying why.
    let request = Request {
        methods: vec![MethodKind::Plate, MethodKind::Classifier],
        ..Request::new(Source::triangles("m", model.clone()), Settings::default())
    };
    let both = convert_all(request, &Cancel::default(), platener::convert::no_progress());
    let reason = both.methods[1]
        .error
        .as_ref()
        .map(ToString::to_string)
        .unwrap_or_default();
    assert!(reason.contains("faces are exact"), "{reason}");
    // Alone, it makes the plate method's plan.
    let state = convert_with(MethodKind::Classifier, model);
    let (plan, v) = checked(&state);
    rebuilds(&v);
    assert_eq!(plan.parts.len(), plate.parts.len());
    assert_eq!(plan.joints.len(), plate.joints.len());
}

/// A finely tessellated (128-sided, effectively round) tube and cone shell: the plate method
/// finds only slivers; the classifier's cylinders and cones become one living-hinge wrap.
#[test]
fn smooth_tubes_and_cone_shells_become_one_bent_wrap() {
    let tube = samples::tube(128, 50.0, 60.0, 3.0);
    let shade = samples::cone_shell(128, 70.0, 45.0, 60.0, 3.0);
    for (name, model, kind) in [
        ("tube", tube, SurfaceKind::Cylinder),
        ("shade", shade, SurfaceKind::Cone),
    ] {
        let state = convert_with(MethodKind::Classifier, model);
        let found = state.classify.as_ref().expect("classified");
        let curved: Vec<_> = found.primitives.iter().filter(|p| p.shape.kind() == kind).collect();
        assert_eq!(curved.len(), 2, "{name}: the inner and outer wall");
        let (plan, v) = checked(&state);
        rebuilds(&v);
        assert_eq!(plan.parts.len(), 1, "{name}");
        let wrap = &plan.parts[0];
        assert_eq!(wrap.kind, PartKind::Bent, "{name}");
        assert!(wrap.segments.len() >= 8, "{name}: {} facets", wrap.segments.len());
        assert_eq!(wrap.bends.len(), wrap.segments.len() - 1, "{name}");
    }
}

/// A small textured box (60 × 40 × 30, the same bumps): with ε = t / 2 = 1.5 mm, a quarter
/// of its smallest side, cylinders rounding its edges used to take strips of its faces.
#[test]
fn a_small_textured_box_is_still_six_walls() {
    let state = convert_with(
        MethodKind::Classifier,
        samples::textured_box(DVec3::new(60.0, 40.0, 30.0), 3.0, 0.5, 10.0),
    );
    let found = state.classify.as_ref().expect("classified");
    assert!(
        found.primitives.iter().all(|p| p.shape.kind() == SurfaceKind::Plane),
        "{:?}",
        found.primitives.iter().map(|p| p.shape.kind()).collect::<Vec<_>>()
    );
    let (plan, v) = checked(&state);
    rebuilds(&v);
    assert_six_jointed_walls(&plan, [DVec3::X, DVec3::Y, DVec3::Z]);
}

/// A closed box with a solid dome on its lid: the walls become plates, the dome stacked layers
/// on a shaft that goes on through a slot in the lid.
#[test]
fn a_domed_box_becomes_plates_and_a_stack_of_layers_jointed_to_the_lid() {
    let (h, radius, t) = (50.0, 30.0, 3.0);
    let state = convert_with(
        MethodKind::Classifier,
        samples::domed_box(120.0, 90.0, h, t, radius, 96, 24),
    );
    let (plan, v) = checked(&state);
    rebuilds(&v);
    let of = |kind| plan.parts.iter().filter(move |p| p.kind == kind);
    assert_eq!(of(PartKind::Plate).count(), 6, "the box's six walls");
    let layers: Vec<_> = of(PartKind::Layer).collect();
    assert_eq!(layers.len(), 10, "30 mm of dome in 3 mm layers");
    // Each layer lies on the one below, the first on the lid, and its island (before slots are
    // cut) is the dome's section at its mid-plane: a 96-gon's area is 0.07 % under the
    // circle's, the 24 bands' chords take up to 1 % near the top.
    let stack = state.layers.as_ref().and_then(|l| l.stack.as_ref()).expect("a stack");
    for (k, layer) in layers.iter().enumerate() {
        let z = layer.transform[2][3];
        assert!((z - (h + t * k as f64)).abs() < 1e-6, "layer {k} at {z}");
        let mid = z + t / 2.0 - h;
        let section = std::f64::consts::PI * (radius * radius - mid * mid);
        let [island] = &stack.layers[k].islands[..] else {
            panic!("layer {k} is one island")
        };
        assert_eq!(island.part, layer.id);
        let area = island.outline.area();
        assert!((area / section - 1.0).abs() < 0.015, "layer {k}: {area} for {section}");
    }
    let shafts: Vec<_> = of(PartKind::Shaft).collect();
    assert!(!shafts.is_empty());
    // Every shaft through the bottom layer goes on through the lid: a slot joint, a hole in
    // the lid as large as the shaft's end, and the shaft reaching 3 mm below the dome.
    let lid = plan
        .parts
        .iter()
        .find(|p| p.kind == PartKind::Plate && (p.transform[2][3] - h).abs() < 1e-6)
        .expect("the lid");
    let tenons: Vec<_> = plan.joints.iter().filter(|j| j.kind == JointKind::Slot).collect();
    assert!(!tenons.is_empty(), "{:?}", plan.joints);
    assert_eq!(lid.holes.len(), tenons.len());
    for j in &tenons {
        assert_eq!(j.parts[1], lid.id);
        let shaft = shafts.iter().find(|s| s.id == j.parts[0]).expect("a shaft");
        let m = shaft.transform;
        let z = |p: &glam::DVec2| m[2][0] * p.x + m[2][1] * p.y + m[2][3];
        let lowest = shaft.outline.iter().map(z).fold(f64::MAX, f64::min);
        assert!(
            (lowest - (h - t)).abs() < 1e-6,
            "the shaft ends at z = {lowest}, not under the lid"
        );
    }
    let slots: f64 = lid
        .holes
        .iter()
        .map(|h| platener_geom::polygon::signed_area(h).abs())
        .sum();
    assert!(slots > 0.0 && slots < 3.0 * 60.0 * tenons.len() as f64, "{slots}");
    let report = state.layers.as_ref().expect("the layers step ran");
    assert!(report.rests_on.is_some() && report.skipped.is_none());
}

/// A solid peg (r 15, 40 tall) on a box's lid is too narrow for a living hinge to wrap in
/// 3 mm plywood: it becomes stacked discs on a shaft through the lid, not a prism of facets.
#[test]
fn a_small_solid_cylinder_becomes_stacked_discs() {
    let (h, r, tall, t) = (50.0, 15.0, 40.0, 3.0);
    let profile = [DVec2::new(r, 0.0), DVec2::new(r, tall), DVec2::new(0.0, tall)];
    let state = convert_with(
        MethodKind::Classifier,
        samples::knobbed_box(120.0, 90.0, h, t, &profile, 96),
    );
    let found = state.classify.as_ref().expect("classified");
    let peg = found
        .primitives
        .iter()
        .find(|p| p.shape.kind() == SurfaceKind::Cylinder)
        .expect("the peg is a cylinder");
    assert!(peg.outward);
    let (plan, v) = checked(&state);
    rebuilds(&v);
    assert!(plan.parts.iter().all(|p| p.kind != PartKind::Bent));
    let stack = state.layers.as_ref().and_then(|l| l.stack.as_ref()).expect("a stack");
    // The peg's discs: 13 layers (40 mm in 3 mm), every one a single island of the circle's
    // area (a 96-gon's, less 0.07 %) within 1 %, the first on the lid.
    let layers = &stack.layers;
    assert_eq!(layers.len(), 13);
    for (k, layer) in layers.iter().enumerate() {
        let [island] = &layer.islands[..] else {
            panic!("layer {k} is one disc")
        };
        let area = island.outline.area();
        let disc = std::f64::consts::PI * r * r;
        assert!((area / disc - 1.0).abs() < 0.01, "layer {k}: {area} for {disc}");
    }
    assert!((stack.layer_frame(0).origin.z - h).abs() < 1e-6);
    let tenons = &state.layers.as_ref().expect("layers").tenons;
    assert!(!tenons.is_empty());
    let walls = plan.parts.iter().filter(|p| p.kind == PartKind::Plate).count();
    assert_eq!(walls, 6, "the box's walls");
    // With bending off the peg stays what the plate method makes of it: facet plates.
    let settings = Settings {
        thicknesses: vec![3.0],
        bending: platener::Bending::None,
        ..Settings::default()
    };
    let source = Source::triangles("peg", samples::knobbed_box(120.0, 90.0, h, t, &profile, 96));
    let plain = convert(MethodKind::Classifier, source, settings, &Cancel::default()).expect("converts");
    let (plan, _) = checked(&plain);
    assert!(plan.parts.iter().all(|p| p.kind == PartKind::Plate) && plan.parts.len() > 6);
}

/// Models the plates explain whole get no layers: the classifier's plan of a clean box is its
/// six walls, with nothing left over for the layers step.
#[test]
fn a_box_leaves_nothing_to_the_layers() {
    let state = convert_with(MethodKind::Classifier, samples::closed_box(120.0, 90.0, 70.0, 3.0));
    let layers = state.layers.as_ref().expect("the layers step ran");
    assert!(layers.stack.is_none() && layers.skipped.is_some(), "{layers:?}");
    assert!(layers.marked_share < 0.001);
}

/// The classifier's plan of a corpus model, or `None` (with a message) without the corpus.
fn corpus_plan(name: &str) -> Option<State> {
    let dir = samples::shared_corpus().map_err(|m| eprintln!("{m}")).ok()?;
    // Asked for alone, the classifier runs on exact faces too (the house's walls are).
    let settings = Settings {
        thicknesses: vec![3.0],
        ..Settings::default()
    };
    let source = Source::File(dir.join(name));
    Some(convert(MethodKind::Classifier, source, settings, &Cancel::default()).expect("converts"))
}

/// The Utah teapot: its flat lid top is a plate in the middle of the body's layers. Shafts pass
/// through the plate as through a layer, so the layers are jointed to it and the plan holds
/// together; the layers nothing holds (the spout's) are left out, with a warning.
#[test]
fn the_teapots_layers_are_threaded_through_its_lid_plate() {
    let Some(state) = corpus_plan("organic/utah_teapot.stl") else {
        return;
    };
    let (plan, v) = checked(&state);
    assert!(v.passed(), "{:?}", v.problems);
    let layers = state.layers.as_ref().expect("the layers step ran");
    let stack = layers.stack.as_ref().expect("layers were made");
    assert!(!layers.tenons.is_empty());
    for [shaft, plate] in &layers.tenons {
        let plate = plan.parts.iter().find(|p| p.id == *plate).expect("the plate");
        assert_eq!(plate.kind, PartKind::Plate);
        assert!(
            !plate.holes.is_empty(),
            "the shaft's slot is cut into plate {}",
            plate.id
        );
        assert!(
            plan.joints
                .iter()
                .any(|j| j.kind == JointKind::Slot && j.parts == [*shaft, plate.id])
        );
    }
    // Only layers a shaft holds to the plate are in the plan.
    let shafts: Vec<_> = plan.parts.iter().filter(|p| p.kind == PartKind::Shaft).collect();
    assert_eq!(shafts.len(), stack.shafts.len());
    assert!(layers.left_out > 0);
    let warned = state
        .records
        .iter()
        .flat_map(|r| &r.warnings)
        .any(|w| w.message.contains("left out"));
    assert!(warned);
}

/// A house whose only freeform is a sliver of its roof: no shaft can hold that layer to a
/// plate, so it is left out rather than shipped as a loose part, and the plan stays the
/// plate method's.
#[test]
fn layers_nothing_holds_are_left_out() {
    let Some(state) = corpus_plan("plates/model_house_walls.stl") else {
        return;
    };
    let (plan, v) = checked(&state);
    assert!(v.passed(), "{:?}", v.problems);
    assert!(plan.parts.iter().all(|p| p.kind == PartKind::Plate));
    let layers = state.layers.as_ref().expect("the layers step ran");
    assert!(layers.stack.is_none() && layers.left_out > 0, "{layers:?}");
}

/// The corpus's XYZ calibration cube has engraved letters: fragments enough for the classifier
/// to run, but its primitives replace none of the exact faces and leave no surface for layers.
/// Beside the plate method it says so once plates are made (it used to make the same plan
/// through joints, parts and nesting); alone, it converts.
#[test]
fn beside_the_plate_method_the_classifier_stops_when_it_would_repeat_its_plan() {
    let Some(dir) = samples::shared_corpus().map_err(|m| eprintln!("{m}")).ok() else {
        return;
    };
    let path = dir.join("solids/xyz_calibration_cube_20mm.stl");
    let request = Request {
        methods: vec![MethodKind::Plate, MethodKind::Classifier],
        ..Request::new(Source::File(path.clone()), Settings::default())
    };
    let both = convert_all(request, &Cancel::default(), platener::convert::no_progress());
    let classifier = &both.methods[1];
    assert_eq!(classifier.status, platener::convert::Status::Skipped);
    let reason = classifier.error.as_ref().map(ToString::to_string).unwrap_or_default();
    assert!(reason.contains("would be the plate method's"), "{reason}");
    let state = classifier.state.as_ref().expect("the steps before stay");
    assert!(state.classify.as_ref().is_some_and(|c| c.replaced.is_empty()));
    assert!(state.plates.is_some() && state.bends.is_none());
    let alone = convert(
        MethodKind::Classifier,
        Source::File(path),
        Settings::default(),
        &Cancel::default(),
    )
    .expect("converts alone");
    assert!(alone.export.is_some());
}
