//! The score ranks plans as a maker would: pairs whose order is known, asserted as an order
//! (never as magic values); and convert's report, the score and `verify` agree because they
//! read one analysis of the assembly.
//!
//! Corpus models are skipped with a message when the shared corpus is absent (CI requires it).

use std::path::{Path, PathBuf};

use platener::convert::{Request, Status, convert_all, no_progress};
use platener::method::MethodKind;
use platener::pipeline::State;
use platener::plan::Plan;
use platener::score::{Score, score};
use platener::verify::{Check, verify};
use platener::{Cancel, Settings, Source, Weld, convert};
use platener_fixtures::samples;

/// A model of the shared corpus, or `None` after saying why the test skips.
fn corpus_model(relative: &str) -> Option<PathBuf> {
    let dir = samples::shared_corpus().map_err(|m| eprintln!("{m}")).ok()?;
    let path = dir.join(relative);
    assert!(path.is_file(), "the corpus lacks {relative}");
    Some(path)
}

/// The plate method's conversion of `path` with `weld`.
fn plate(path: &Path, weld: Weld) -> State {
    let settings = Settings {
        weld,
        ..Settings::default()
    };
    convert(
        MethodKind::Plate,
        Source::File(path.to_path_buf()),
        settings,
        &Cancel::default(),
    )
    .expect("converts")
}

/// The score of a converted state's own plan.
fn score_of(c: &State) -> Score {
    score(
        c.mesh.as_deref().expect("mesh"),
        c.bundle().expect("plan"),
        c.plates.as_deref(),
    )
}

/// The score of another plan for the state's model (the plan put into a copy of its bundle).
fn score_plan(c: &State, plan: Plan) -> Score {
    let mut bundle = (**c.bundle().expect("plan")).clone();
    bundle.plan = plan;
    score(c.mesh.as_deref().expect("mesh"), &bundle, None)
}

#[test]
fn the_photo_frame_unwelded_ranks_above_the_welded() {
    let Some(path) = corpus_model("plates/photo_frame_5inch_two_parts.stl") else {
        return;
    };
    let (clean, welded) = (plate(&path, Weld::Off), plate(&path, Weld::Distance(1.8)));
    let (a, b) = (score_of(&clean), score_of(&welded));
    assert!(a.total > b.total, "weld off {a:#?}\nwelded {b:#?}");
    // What makes the difference: the welded plan's joints are not at the model's angles.
    assert!(
        a.quality.fidelity > b.quality.fidelity,
        "{:?} vs {:?}",
        a.quality,
        b.quality
    );
}

#[test]
fn the_parts_tray_ranks_above_the_welded_photo_frame() {
    let (Some(tray), Some(frame)) = (
        corpus_model("plates/parts_tray_drawer_holder.stl"),
        corpus_model("plates/photo_frame_5inch_two_parts.stl"),
    ) else {
        return;
    };
    let (a, b) = (
        score_of(&plate(&tray, Weld::Auto)),
        score_of(&plate(&frame, Weld::Distance(1.8))),
    );
    assert!(a.total > b.total, "tray {a:#?}\nwelded frame {b:#?}");
}

fn box_conversion() -> State {
    let source = Source::triangles("box", samples::closed_box(100.0, 80.0, 60.0, 3.0));
    convert(MethodKind::Plate, source, Settings::default(), &Cancel::default()).expect("converts")
}

#[test]
fn a_clean_box_ranks_above_the_box_with_a_wall_removed() {
    let c = box_conversion();
    let clean = score_of(&c);
    let mut plan = c.bundle().expect("plan").plan.clone();
    plan.parts.retain(|p| p.id != 1);
    plan.joints.retain(|j| !j.parts.contains(&1));
    let open = score_plan(&c, plan);
    assert!(clean.total > open.total, "clean {clean:#?}\nopen {open:#?}");
    assert!(clean.surface.value > open.surface.value);
}

#[test]
fn a_clean_box_ranks_above_the_box_with_a_loose_part() {
    let c = box_conversion();
    let clean = score_of(&c);
    let mut plan = c.bundle().expect("plan").plan.clone();
    plan.joints.retain(|j| !j.parts.contains(&3));
    let loose = score_plan(&c, plan.clone());
    assert!(clean.total > loose.total, "clean {clean:#?}\nloose {loose:#?}");
    assert_eq!((clean.assembly.groups, loose.assembly.groups), (1, 2));
    // And verify fails it, naming the loose part.
    let v = verify(&plan, c.mesh.as_deref());
    let groups: Vec<_> = v.failures.iter().filter(|f| f.check == Check::Groups).collect();
    assert_eq!(groups.len(), 1, "{:?}", v.problems);
    assert_eq!(groups[0].parts, vec![3]);
}

/// Convert's report (its verification and the score's groups), the score and `verify` of the
/// ZIP's plan.json give the same groups, joints that do not meet and interference; and the
/// method named best passes verify whenever one does.
#[test]
fn convert_score_and_verify_agree_on_corpus_plans() {
    let names = [
        "plates/photo_frame_5inch_two_parts.stl",
        "plates/arduino_uno_enclosure.stl",
        "plates/acrylic_case_corner_bracket_5mm.stl",
        "solids/xyz_calibration_cube_20mm.stl",
    ];
    for name in names {
        let Some(path) = corpus_model(name) else {
            return;
        };
        let all = convert_all(
            Request::new(Source::File(path), Settings::default()),
            &Cancel::default(),
            no_progress(),
        );
        let mut any_passed = false;
        for m in all.methods.iter().filter(|m| m.status == Status::Converted) {
            let (s, v) = (
                m.score.as_ref().expect("score"),
                m.verification.as_ref().expect("verdict"),
            );
            let state = m.state.as_ref().expect("state");
            let plan = platener::verify::plan_from_zip(&m.bundle().expect("plan").zip).expect("plan.json");
            let again = verify(&plan, state.mesh.as_deref());
            let what = format!("{name} {}", m.method.name());
            assert_eq!(s.assembly.groups, v.groups, "{what}");
            assert_eq!(again.groups, v.groups, "{what}");
            assert_eq!(again.group_parts, v.group_parts, "{what}");
            assert_eq!(s.assembly.joints_not_meeting, v.joints_not_meeting, "{what}");
            assert_eq!(again.joints_not_meeting, v.joints_not_meeting, "{what}");
            assert_eq!(s.assembly.interference, v.interference_share, "{what}");
            assert_eq!(again.interference_share, v.interference_share, "{what}");
            assert_eq!(Some(s.surface.value), v.surface_covered, "{what}");
            assert_eq!(again.surface_covered, v.surface_covered, "{what}");
            assert_eq!(again.problems, v.problems, "{what}");
            any_passed |= v.passed();
        }
        let best = all.best().expect("a method converted");
        let best_passed = best.verification.as_ref().is_some_and(|v| v.passed());
        assert_eq!(best_passed, any_passed, "{name}: best {}", best.method.name());
    }
}
