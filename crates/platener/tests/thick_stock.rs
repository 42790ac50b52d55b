//! Stock thicker than the model's walls is said (issue 32, item 6): a case with 1.5 mm walls
//! converted with 3 mm sheets is told the wall found and the settings to change; the same case
//! with 3 mm walls is not.

use platener::method::MethodKind;
use platener::{Cancel, Settings, Source, State, WarningKind, convert};
use platener_fixtures::samples;

fn plate_method(wall: f64) -> State {
    let model = samples::open_box(120.0, 80.0, 40.0, wall);
    convert(
        MethodKind::Plate,
        Source::triangles("case", model),
        Settings::default(),
        &Cancel::default(),
    )
    .expect("converts")
}

/// The wall in the message, mm.
fn wall_said(state: &State) -> Option<f64> {
    state
        .warnings()
        .filter(|w| w.kind == WarningKind::Plates && w.message.contains("thicker than the model's walls"))
        .find_map(|w| {
            let at = w.message.find("(about ")? + "(about ".len();
            w.message[at..].split(' ').next()?.parse().ok()
        })
}

#[test]
fn a_case_with_thin_walls_is_told_its_wall_and_what_to_do() {
    let state = plate_method(1.5);
    let wall = wall_said(&state).expect("the thin walls are reported");
    assert!((wall - 1.5).abs() <= 0.3, "wall {wall}");
    let message = state
        .warnings()
        .find(|w| w.message.contains("thicker than the model's walls"))
        .map(|w| w.message.clone())
        .unwrap_or_default();
    assert!(
        message.contains("`thickness`") && message.contains("`scale`"),
        "{message}"
    );
}

#[test]
fn walls_as_thick_as_the_sheet_say_nothing() {
    assert_eq!(wall_said(&plate_method(3.0)), None);
}
