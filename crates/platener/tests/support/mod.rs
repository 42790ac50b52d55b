//! Shared by the integration tests (`mod support;`): the plate method's conversion of a
//! model made in code.

use platener::convert::convert;
use platener::method::MethodKind;
use platener::plan::Material;
use platener::read::Triangle;
use platener::{Bending, Cancel, Settings, Source, State};

/// The plate method's conversion of `model` in sheets of `t` mm of `material`, bending as
/// `bending` says.
pub fn convert_plates(model: Vec<Triangle>, material: Material, t: f64, bending: Bending) -> State {
    let mut settings = Settings {
        thicknesses: vec![t],
        bending,
        ..Settings::default()
    };
    settings.cut.material = material;
    convert(
        MethodKind::Plate,
        Source::triangles("m", model),
        settings,
        &Cancel::default(),
    )
    .expect("converts")
}
