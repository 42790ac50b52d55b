//! The smallest part (issue 32, item 5): one rule for every method, tested on the two
//! cases: a cup with thin curved walls, and a small chair on 4 × 4 mm legs at 2 mm sheet.
//! (The teacup's plate method at 1.5 mm, where joints left 0.7 mm chips, takes seconds in a
//! release build and is measured in docs/performance.md; `parts/small.rs` tests what it does
//! with such chips, and `corpus_plans` holds every corpus plan to the rule.)

use platener::cuttable::{MIN_AREA, Rule, dovetail_keys};
use platener::method::MethodKind;
use platener::plan::{Part, PartKind};
use platener::{Cancel, Settings, Source, State, convert};
use platener_fixtures::samples;

fn converted(method: MethodKind, name: &str, triangles: Vec<platener::read::Triangle>, t: f64) -> State {
    let settings = Settings {
        thicknesses: vec![t],
        ..Settings::default()
    };
    convert(method, Source::triangles(name, triangles), settings, &Cancel::default())
        .unwrap_or_else(|e| panic!("{name} ({method:?}, {t} mm): {e}"))
}

fn parts(state: &State) -> &[Part] {
    &state.final_parts().as_ref().expect("parts").parts
}

/// Every plate, bent part and layer of `state` (joint pieces left out) keeps to the rule.
fn assert_none_too_small(what: &str, state: &State) {
    let input = state.final_parts().as_ref().expect("parts");
    let keys = dovetail_keys(input.joints.iter().map(|j| (j.kind, j.parts)));
    for part in input
        .parts
        .iter()
        .filter(|p| p.kind != PartKind::Shaft && !keys.contains(&p.id))
    {
        let rule = Rule::for_sheet(part.thickness, 0.0, MIN_AREA);
        let verdict = rule.check(&part.polygon).expect("on the grid");
        assert!(verdict.is_ok(), "{what}: part {} {verdict:?}", part.id);
    }
}

#[test]
fn a_teacups_walls_thinner_than_the_sheet_make_no_layer_and_no_part_under_the_rule() {
    let cup = samples::teacup(48, 12, 1.5);
    // From 3 mm sheet the 1.5 mm wall's rings are nowhere 3 mm wide: only the floor is a layer.
    let stacked = converted(MethodKind::Stacked, "teacup", cup.clone(), 3.0);
    assert_none_too_small("stacked 3 mm", &stacked);
    assert_eq!(parts(&stacked).len(), 1, "the floor alone");
    let floor = &parts(&stacked)[0];
    assert!(floor.polygon.area() > 1500.0, "{}", floor.polygon.area());
    let dropped = &stacked.stacked.as_ref().expect("stack").dropped;
    assert!(
        dropped.len() >= 15,
        "the wall's rings are left out and said: {}",
        dropped.len()
    );
    // From 1.5 mm sheet the rings are as wide as the sheet is thick: they are made.
    let thin = converted(MethodKind::Stacked, "teacup", cup.clone(), 1.5);
    assert_none_too_small("stacked 1.5 mm", &thin);
    assert!(parts(&thin).len() >= 30, "{}", parts(&thin).len());
    let classifier = converted(MethodKind::Classifier, "teacup", cup, 3.0);
    assert_none_too_small("classifier 3 mm", &classifier);
}

#[test]
fn a_small_chairs_4_mm_legs_are_kept_at_2_mm() {
    let state = converted(MethodKind::Plate, "chair", samples::small_chair(), 2.0);
    assert_none_too_small("plate 2 mm", &state);
    let legs: Vec<&Part> = parts(&state)
        .iter()
        .filter(|p| {
            let (lo, hi) = p.polygon.bounds();
            let size = hi - lo;
            (size.min_element() - 4.0).abs() < 0.01 && size.max_element() >= 40.0
        })
        .collect();
    assert_eq!(legs.len(), 8, "two 4 mm plates per leg");
    assert!(
        !state
            .warnings()
            .any(|w| w.message.contains("too small to cut and hold")),
        "nothing is left out"
    );
}
