//! Raised details on stacked layers (issue 32, item 1): lettering standing less than a layer
//! high on an exposed face is engraved on that face; slopes (a sphere's top, a figure's
//! shoulder) are not details. Asserted on plan.json's marks: where they are, which face, how
//! much of the letters' footprint their outlines enclose.

use platener::glam::{DVec2, DVec3};
use platener::method::MethodKind;
use platener::plan::{MarkKind, MarkSide, Part};
use platener::{Cancel, Settings, Source, State, convert};
use platener_fixtures::samples;

fn stacked(name: &str, model: Vec<platener::read::Triangle>) -> State {
    convert(
        MethodKind::Stacked,
        Source::triangles(name, model),
        Settings::default(),
        &Cancel::default(),
    )
    .unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn parts(state: &State) -> &[Part] {
    &state.final_parts().as_ref().expect("parts").parts
}

/// The area a closed ring encloses (shoelace, unsigned).
fn ring_area(ring: &[DVec2]) -> f64 {
    let n = ring.len();
    (0..n).map(|i| ring[i].perp_dot(ring[(i + 1) % n])).sum::<f64>().abs() / 2.0
}

/// The keychain tag's letters come back as score marks on its one layer's upper face (the
/// face down on the sheet), enclosing at least 80 % of the letters' footprint and lying over
/// the letters in the model.
#[test]
fn a_keychain_keeps_its_raised_letters_as_engraving() {
    let state = stacked("keychain", samples::keychain_tag());
    let stack = state.stacked.as_ref().expect("stacked");
    assert_eq!(stack.raised.len(), 1, "{:?}", stack.raised);
    let ps = parts(&state);
    let layers: Vec<&Part> = ps
        .iter()
        .filter(|p| p.kind == platener::plan::PartKind::Layer)
        .collect();
    assert_eq!(layers.len(), 1);
    let tag = layers[0];
    let letters: Vec<&Vec<DVec2>> = tag
        .marks
        .iter()
        .filter(|m| m.kind == MarkKind::Score && m.side == Some(MarkSide::Bottom))
        .map(|m| &m.path)
        .collect();
    let want: f64 = samples::KEYCHAIN_STROKES
        .iter()
        .map(|(x0, y0, x1, y1)| (x1 - x0) * (y1 - y0))
        .sum();
    let got: f64 = letters.iter().map(|r| ring_area(r)).sum();
    assert!(
        got >= 0.8 * want && got <= 1.05 * want,
        "engraved {got:.1} mm² of {want:.1} mm²"
    );
    // Every engraved point lies on a letter's edge in the model, on the base's top.
    for p in letters.iter().flat_map(|r| r.iter()) {
        let m = tag.frame.to_model(p.extend(0.0));
        let on_edge = samples::KEYCHAIN_STROKES.iter().any(|&(x0, y0, x1, y1)| {
            let inside = m.x > x0 - 0.01 && m.x < x1 + 0.01 && m.y > y0 - 0.01 && m.y < y1 + 0.01;
            let edge = [m.x - x0, x1 - m.x, m.y - y0, y1 - m.y].iter().any(|d| d.abs() < 0.01);
            inside && edge
        });
        assert!(on_edge, "engraved point {m:?} is on no letter's edge");
    }
    assert!(
        state.warnings().any(|w| w.message.contains("lettering or relief")),
        "the report says so"
    );
}

/// A sphere's layers narrow at every step: no face carries a detail, no mark but the layers'
/// own numbers.
#[test]
fn a_sphere_has_no_raised_details() {
    let state = stacked("sphere", samples::sphere(DVec3::splat(50.0), 40.0, 48, 24));
    let stack = state.stacked.as_ref().expect("stacked");
    assert!(stack.raised.is_empty(), "{:?}", stack.raised);
    assert!(
        parts(&state)
            .iter()
            .flat_map(|p| &p.marks)
            .all(|m| m.side != Some(MarkSide::Bottom)),
        "nothing engraved on an upper face"
    );
}
