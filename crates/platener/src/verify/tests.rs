use super::*;
use crate::convert::convert;
use crate::method::MethodKind;
use crate::pipeline::{Cancel, Source};
use crate::settings::Settings;
use platener_fixtures::samples;

fn check(model: Vec<crate::read::Triangle>) -> Verification {
    let source = Source::triangles("m", model);
    let c = convert(MethodKind::Plate, source, Settings::default(), &Cancel::default()).expect("converts");
    let bundle = c.bundle().expect("plan");
    verify(&bundle.plan, c.mesh.as_deref())
}

#[test]
fn the_box_assembles_without_interference_and_covers_the_model() {
    let v = check(samples::closed_box(100.0, 80.0, 60.0, 3.0));
    assert!(v.passed(), "{:?}", v.problems);
    assert_eq!(v.parts, 6);
    assert!(v.interference_share < 0.001, "{}", v.interference_share);
    assert_eq!(v.groups, 1);
    assert!(
        v.surface_covered.expect("model given") >= 0.98,
        "{:?}",
        v.surface_covered
    );
    assert!(v.volume_inside.expect("model given") > 0.99, "{:?}", v.volume_inside);
}

#[test]
fn shelf_crossing_and_roof_assemble_without_interference() {
    for model in [
        samples::shelf(80.0, 120.0, 50.0, 60.0, 3.0),
        samples::crossing_plates(100.0, 3.0),
        samples::roof(50.0, 30.0, 80.0, 3.0),
    ] {
        let v = check(model);
        assert!(v.passed(), "{:?}", v.problems);
        assert!(v.interference_share < 0.001, "{}", v.interference_share);
        assert_eq!(v.groups, 1);
    }
}

#[test]
fn overlapping_parts_are_caught() {
    let source = Source::triangles("m", samples::closed_box(100.0, 80.0, 60.0, 3.0));
    let c = convert(MethodKind::Plate, source, Settings::default(), &Cancel::default()).expect("converts");
    let mut plan = c.bundle().expect("plan").plan.clone();
    // Move part 2 by 1.5 mm into the box: it now cuts into its neighbours.
    for row in 0..3 {
        plan.parts[1].transform[row][3] -= plan.parts[1].transform[row][2] * 1.5;
    }
    plan.joints.clear();
    let v = verify(&plan, None);
    assert!(!v.passed());
    assert!(v.interference_share > 0.0);
    assert_eq!(v.groups, 6, "without joints nothing holds");
}

#[test]
fn a_cardboard_box_snaps_together_with_jim_joints() {
    let source = Source::triangles("m", samples::closed_box(100.0, 80.0, 60.0, 3.0));
    let mut settings = Settings::default();
    settings.cut.material = crate::plan::Material::Cardboard;
    let c = convert(MethodKind::Plate, source, settings, &Cancel::default()).expect("converts");
    let plan = &c.bundle().expect("plan").plan;
    assert!(plan.joints.iter().all(|j| j.kind == crate::plan::JointKind::Jim));
    let v = verify(plan, c.mesh.as_deref());
    assert!(!v.interference.is_empty(), "the barbs overlap on purpose");
    assert!(v.passed(), "{:?}", v.problems);
}

/// The coarsest ball (8 × 6 facets, 40 mm radius, corners at 135° to 150°): where fingers
/// would cut a small facet apart, the joint becomes a lap (one finger each) rather than a
/// butt joint, whose square-cut ends would meet only along a line. Every joint meets. The
/// ball as an STL file stores it (single precision), which has two such joints.
#[test]
fn coarse_ball_joints_all_meet() {
    let ball = samples::sphere(glam::DVec3::ZERO, 40.0, 8, 6);
    let stored = ball.into_iter().map(|t| t.map(|v| v.as_vec3().as_dvec3())).collect();
    let v = check(stored);
    assert!(v.passed(), "{:?}", v.problems);
    assert!(v.joints_not_meeting.is_empty(), "{:?}", v.joints_not_meeting);
    assert_eq!(v.groups, 1);
    assert!(v.interference_share < 0.001, "{}", v.interference_share);
}

/// A plan that leaves walls out fails against its model: it does not reproduce it, even when
/// what is there holds together and nothing intersects.
#[test]
fn a_plan_that_covers_too_little_of_the_model_fails() {
    let source = Source::triangles("box", samples::closed_box(100.0, 80.0, 60.0, 3.0));
    let c = convert(MethodKind::Plate, source, Settings::default(), &Cancel::default()).expect("converts");
    let mut plan = c.bundle().expect("plan").plan.clone();
    // The two largest walls (100 × 80 mm: 2 × 8000 of the box's 2 × 21 600 mm² outside, and
    // their inside faces) gone: about 37 % of the surface left uncovered.
    plan.parts.retain(|p| p.id > 2);
    plan.joints.retain(|j| j.parts.iter().all(|&id| id > 2));
    let mesh = c.mesh.as_deref();
    let v = verify(&plan, mesh);
    let covered = v.surface_covered.expect("model given");
    assert!(covered < 0.8, "{covered}");
    assert!(
        v.problems
            .iter()
            .any(|p| p.contains("reproduce only") && p.contains("at least 80 %")),
        "{:?}",
        v.problems
    );
    assert_eq!(v.cover_distance, 2.0);
    // A lower threshold passes the coverage check (the rest still holds).
    let lenient = verify_with(&plan, mesh, 0.5);
    assert!(
        lenient.problems.iter().all(|p| !p.contains("reproduce only")),
        "{:?}",
        lenient.problems
    );
}

/// The box's plan, converted once per test.
fn box_plan() -> (crate::pipeline::State, Plan) {
    let source = Source::triangles("box", samples::closed_box(100.0, 80.0, 60.0, 3.0));
    let c = convert(MethodKind::Plate, source, Settings::default(), &Cancel::default()).expect("converts");
    let plan = c.bundle().expect("plan").plan.clone();
    (c, plan)
}

fn failures_of(v: &Verification, check: Check) -> Vec<&Failure> {
    v.failures.iter().filter(|f| f.check == check).collect()
}

#[test]
fn overlapping_parts_fail_naming_the_pair() {
    let (_, mut plan) = box_plan();
    // Part 2 moved 1.5 mm along its normal: it cuts into the walls it is jointed to.
    for row in 0..3 {
        plan.parts[1].transform[row][3] -= plan.parts[1].transform[row][2] * 1.5;
    }
    let v = verify(&plan, None);
    let f = failures_of(&v, Check::Interference);
    assert_eq!(f.len(), 1, "{:?}", v.problems);
    assert!(f[0].parts.contains(&2), "{:?}", f[0]);
    assert!(
        f[0].message.contains("parts 2 and") || f[0].message.contains("and 2 ("),
        "{}",
        f[0].message
    );
}

#[test]
fn a_loose_part_fails_as_a_group_the_model_does_not_have() {
    let (c, mut plan) = box_plan();
    plan.joints.retain(|j| !j.parts.contains(&3));
    let v = verify(&plan, c.mesh.as_deref());
    let f = failures_of(&v, Check::Groups);
    assert_eq!(f.len(), 1, "{:?}", v.problems);
    assert_eq!(f[0].parts, vec![3]);
    assert!(f[0].message.contains("[3]"), "{}", f[0].message);
    assert_eq!(v.group_parts, vec![vec![1, 2, 4, 5, 6], vec![3]]);
}

#[test]
fn a_part_past_its_sheet_or_larger_than_it_fails() {
    let (_, mut plan) = box_plan();
    plan.parts[0].sheet.x += plan.sheets[0].width;
    let v = verify(&plan, None);
    let f = failures_of(&v, Check::Sheet);
    assert_eq!(f.len(), 1, "{:?}", v.problems);
    assert_eq!(f[0].parts, vec![1]);
    assert!(f[0].message.contains("reaches outside sheet 0"), "{}", f[0].message);
    let (_, mut plan) = box_plan();
    for sheet in &mut plan.sheets {
        sheet.width = 50.0;
        sheet.height = 50.0;
    }
    let v = verify(&plan, None);
    let f = failures_of(&v, Check::Sheet);
    assert_eq!(f.len(), 6, "{:?}", v.problems);
    assert!(f[0].message.contains("is larger than sheet"), "{}", f[0].message);
}

/// A part whose outline is the given ring, with the given holes.
fn part_with(outline: Vec<glam::DVec2>, holes: Vec<Vec<glam::DVec2>>) -> crate::plan::PlanPart {
    let (_, plan) = box_plan();
    crate::plan::PlanPart {
        outline,
        holes,
        ..plan.parts[0].clone()
    }
}

fn outline_findings_at(part: &crate::plan::PlanPart) -> Vec<String> {
    outline_findings(part, 0.2)
}

#[test]
fn outline_findings_name_crossings_touches_spikes_and_stray_holes() {
    use glam::DVec2;
    use platener_geom::polygon::rect;
    let d = |x: f64, y: f64| DVec2::new(x, y);
    let square = rect(0.0, 0.0, 10.0, 10.0);
    assert!(outline_findings_at(&part_with(square.clone(), vec![])).is_empty());
    let hole: Vec<DVec2> = rect(2.0, 2.0, 4.0, 4.0).into_iter().rev().collect();
    assert!(outline_findings_at(&part_with(square.clone(), vec![hole.clone()])).is_empty());
    // A bow tie crosses itself at (3.75, 3.75).
    let bow = vec![d(0.0, 0.0), d(10.0, 10.0), d(10.0, 0.0), d(0.0, 6.0)];
    let f = outline_findings_at(&part_with(bow, vec![]));
    assert!(
        f.contains(&"the outline touches itself at (3.750, 3.750)".to_string()),
        "{f:?}"
    );
    // Two squares sharing the corner (10, 10) as one ring: self-touching.
    let touching = vec![
        d(0.0, 0.0),
        d(10.0, 0.0),
        d(10.0, 10.0),
        d(20.0, 10.0),
        d(20.0, 20.0),
        d(10.0, 20.0),
        d(10.0, 10.0),
        d(0.0, 10.0),
    ];
    let f = outline_findings_at(&part_with(touching, vec![]));
    assert!(
        f.iter().any(|m| m.contains("touches itself at (10.000, 10.000)")),
        "{f:?}"
    );
    // A zero-width spike out of the top edge.
    let spike = vec![
        d(0.0, 0.0),
        d(10.0, 0.0),
        d(10.0, 10.0),
        d(5.0, 10.0),
        d(5.0, 15.0),
        d(5.0, 10.0),
        d(0.0, 10.0),
    ];
    let f = outline_findings_at(&part_with(spike, vec![]));
    assert!(
        f.iter()
            .any(|m| m.contains("runs back along itself at (5.000, 15.000)")),
        "{f:?}"
    );
    // A hole outside the outline, a hole crossing it, a hole touching another.
    let outside: Vec<DVec2> = rect(20.0, 2.0, 24.0, 4.0).into_iter().rev().collect();
    let f = outline_findings_at(&part_with(square.clone(), vec![outside]));
    assert_eq!(f, vec!["hole 1 lies outside the outline".to_string()]);
    let crossing: Vec<DVec2> = rect(8.0, 2.0, 12.0, 4.0).into_iter().rev().collect();
    let f = outline_findings_at(&part_with(square.clone(), vec![crossing]));
    assert!(f.iter().any(|m| m.contains("the outline and hole 1 touch")), "{f:?}");
    let next: Vec<DVec2> = rect(4.0, 2.0, 6.0, 4.0).into_iter().rev().collect();
    let f = outline_findings_at(&part_with(square, vec![hole, next]));
    assert!(f.iter().any(|m| m.contains("hole 1 and hole 2 touch")), "{f:?}");
}

#[test]
fn an_invalid_outline_fails_verify_naming_the_part() {
    let (_, mut plan) = box_plan();
    let part = &mut plan.parts[3];
    let (a, b) = (part.outline[0], part.outline[1]);
    part.outline.insert(1, b);
    part.outline.insert(2, a);
    let v = verify(&plan, None);
    let f = failures_of(&v, Check::Outline);
    assert!(!f.is_empty(), "{:?}", v.problems);
    assert!(f.iter().all(|f| f.parts == vec![4]), "{f:?}");
    assert!(f[0].message.starts_with("part 4: invalid outline"), "{}", f[0].message);
}

/// What convert reports, the score and verify come from one analysis: they agree.
#[test]
fn convert_score_and_verify_agree_on_the_box() {
    let (c, plan) = box_plan();
    let mesh = c.mesh.as_deref();
    let v = verify(&plan, mesh);
    let s = crate::score::score(mesh.expect("mesh"), c.bundle().expect("bundle"), None);
    assert!(v.passed(), "{:?}", v.problems);
    assert_eq!(s.assembly.groups, v.groups);
    assert_eq!(s.assembly.joints_not_meeting, v.joints_not_meeting);
    assert_eq!(Some(s.surface.value), v.surface_covered);
    assert_eq!(s.assembly.interference, v.interference_share);
}

#[test]
fn verify_welds_the_model_as_the_plan_records() {
    // A plate plan records the weld its mesh was made with; a stacked plan welds nothing.
    let model = samples::closed_box(100.0, 80.0, 60.0, 3.0);
    let settings = Settings {
        weld: crate::Weld::Distance(0.5),
        ..Settings::default()
    };
    let plate = convert(
        MethodKind::Plate,
        Source::triangles("m", model.clone()),
        settings.clone(),
        &Cancel::default(),
    )
    .expect("converts");
    let welded = plate.weld.as_deref().expect("welded").distance;
    assert!(welded > 0.0, "{welded}");
    assert_eq!(
        model_weld(&plate.bundle().expect("plan").plan),
        crate::Weld::Distance(welded)
    );
    let stacked = convert(
        MethodKind::Stacked,
        Source::triangles("m", model),
        settings,
        &Cancel::default(),
    )
    .expect("converts");
    assert_eq!(model_weld(&stacked.bundle().expect("plan").plan), crate::Weld::Off);
}
