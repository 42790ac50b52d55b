//! Every part is held (issue 15): crossing plates stay whole with halving joints, corners close,
//! nothing overlaps, no loose fragments. Asserted on the assembled geometry: part counts,
//! rebuilt volumes against the model's, interference between the parts.

use platener::glam::DVec3;
use platener::joints::ConnectionKind;
use platener::method::MethodKind;
use platener::plan::Material;
use platener::read::Triangle;
use platener::verify::verify;
use platener::{Cancel, Settings, Source, State, convert, samples};
use platener_geom::Polygon;
use platener_geom::offset::offset;
use proptest::prelude::*;

/// The plate method's conversion of `model` with sheets of `t` mm (wood unless `card`).
fn convert_plates(model: Vec<Triangle>, t: f64, card: bool) -> State {
    let mut settings = Settings {
        thicknesses: vec![t],
        ..Settings::default()
    };
    if card {
        settings.cut.material = Material::Cardboard;
    }
    convert(
        MethodKind::Plate,
        Source::triangles("m", model),
        settings,
        &Cancel::default(),
    )
    .expect("converts")
}

/// What the assembled parts are, measured.
#[derive(Debug)]
struct Assembled {
    parts: usize,
    halved: usize,
    volume: f64,
    model_volume: f64,
    interference: f64,
    groups: usize,
}

fn assemble(state: &State) -> Assembled {
    let plates = state.plates.as_ref().expect("plates");
    let joints = state.joints.as_ref().expect("joints");
    let slabs = joints.parts(&plates.plates);
    let bundle = state.bundle().expect("plan");
    let v = verify(&bundle.plan, state.mesh.as_deref());
    let model_volume = state
        .mesh
        .as_ref()
        .and_then(|m| m.health.volume)
        .expect("a closed model");
    Assembled {
        parts: bundle.plan.parts.len(),
        halved: joints
            .connections
            .iter()
            .filter(|c| c.kind == ConnectionKind::Cross)
            .count(),
        volume: slabs.iter().map(|s| s.volume()).sum(),
        model_volume,
        interference: v.interference.iter().map(|i| i.volume).sum(),
        groups: v.groups,
    }
}

/// Plates `t` thick standing on z = 0, `depth` tall: `ys.len()` along x (at y = `ys[k]` to
/// `ys[k] + t`) crossing `xs.len()` along y, each running `margin` past the outermost
/// crossing plate (an egg crate; one of each is a "+").
fn egg_crate(xs: &[f64], ys: &[f64], t: f64, margin: f64, depth: f64) -> Vec<Triangle> {
    let cuts = |at: &[f64]| {
        let mut c = vec![at[0] - margin];
        for &a in at {
            c.extend([a, a + t]);
        }
        c.push(at[at.len() - 1] + t + margin);
        c
    };
    let (cx, cy) = (cuts(xs), cuts(ys));
    // Cells 1, 3, 5, … across each list are the plates.
    samples::voxels(&cx, &cy, &[0.0, depth], |i, j, _| i % 2 == 1 || j % 2 == 1)
}

/// A truncated cone of `facets` flat sides: radius `r0` at z = 0, `r1` at z = `h`.
fn frustum(facets: usize, r0: f64, r1: f64, h: f64) -> Vec<Triangle> {
    let at = |r: f64, k: usize, z: f64| {
        let a = std::f64::consts::TAU * k as f64 / facets as f64;
        DVec3::new(r * a.cos(), r * a.sin(), z)
    };
    let (bottom, top) = (DVec3::ZERO, DVec3::new(0.0, 0.0, h));
    let mut out = Vec::new();
    for k in 0..facets {
        let (b0, b1, t0, t1) = (at(r0, k, 0.0), at(r0, k + 1, 0.0), at(r1, k, h), at(r1, k + 1, h));
        out.extend([[b0, b1, t1], [b0, t1, t0], [bottom, b1, b0], [top, t0, t1]]);
    }
    out
}

#[test]
fn a_plus_of_two_plates_is_two_parts_with_a_halving_joint() {
    // Off centre: the crossing 20 mm from one end of each plate.
    let model = egg_crate(&[20.0], &[35.0], 3.0, 20.0, 40.0);
    let a = assemble(&convert_plates(model, 3.0, false));
    eprintln!("{a:?}");
    assert_eq!((a.parts, a.halved, a.groups), (2, 1, 1), "{a:?}");
    assert!((a.volume - a.model_volume).abs() < 1e-3 * a.model_volume, "{a:?}");
    assert!(a.interference < 1e-6 * a.model_volume, "{a:?}");
}

#[test]
fn an_x_of_two_plates_is_two_parts_with_a_halving_joint() {
    let model = samples::fan(&[0.0, 50.0, 180.0, 230.0], 40.0, 3.0, 40.0);
    let a = assemble(&convert_plates(model, 3.0, false));
    eprintln!("{a:?}");
    assert_eq!((a.parts, a.halved, a.groups), (2, 1, 1), "{a:?}");
    assert!((a.volume - a.model_volume).abs() < 1e-3 * a.model_volume, "{a:?}");
    assert!(a.interference < 1e-6 * a.model_volume, "{a:?}");
}

#[test]
fn a_truncated_cone_of_card_has_no_overlap() {
    let model = frustum(24, 40.0, 25.0, 50.0);
    let a = assemble(&convert_plates(model, 1.5, true));
    eprintln!("{a:?}");
    assert_eq!(a.groups, 1, "{a:?}");
    assert!(a.interference < 1e-4 * a.volume, "{a:?}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(6))]
    #[test]
    fn crossing_grids_are_n_plus_m_parts(
        n in 1usize..=5,
        m in 1usize..=5,
        gap in 12.0f64..30.0,
        margin in 8.0f64..25.0,
        depth in 15.0f64..40.0,
    ) {
        let xs: Vec<f64> = (0..m).map(|k| k as f64 * gap).collect();
        let ys: Vec<f64> = (0..n).map(|k| k as f64 * (gap + 3.5)).collect();
        let a = assemble(&convert_plates(egg_crate(&xs, &ys, 3.0, margin, depth), 3.0, false));
        prop_assert_eq!((a.parts, a.halved, a.groups), (n + m, n * m, 1), "{:?}", a);
        prop_assert!((a.volume - a.model_volume).abs() < 1e-3 * a.model_volume, "{:?}", a);
        prop_assert!(a.interference < 1e-6 * a.model_volume, "{:?}", a);
    }
}

/// The plate method's conversion of a corpus model (3 mm wood), or `None` after saying why
/// the test skips (CI fails instead).
fn corpus_plates(file: &str) -> Option<State> {
    let dir = samples::shared_corpus().map_err(|m| eprintln!("{m}")).ok()?;
    let path = samples::stl_files(&dir)
        .into_iter()
        .find(|p| p.file_name().is_some_and(|n| n == file))
        .unwrap_or_else(|| panic!("{file} is not in the corpus"));
    let settings = Settings::default();
    Some(convert(MethodKind::Plate, Source::File(path), settings, &Cancel::default()).expect("converts"))
}

/// How many pieces a part's outline falls into when every point within `t` of its edge is
/// taken away: more than one where it has a neck narrower than 2·t.
fn pieces_after_inset(outline: &Polygon, t: f64) -> usize {
    offset(std::slice::from_ref(outline), -t).expect("grid").len()
}

#[test]
fn arduino_enclosure_is_one_group_with_its_corners_joined() {
    let Some(state) = corpus_plates("arduino_uno_enclosure.stl") else {
        return;
    };
    let plates = state.plates.as_ref().expect("plates");
    let joints = state.joints.as_ref().expect("joints");
    let walls: Vec<usize> = (0..plates.plates.len())
        .filter(|&i| plates.plates[i].frame.n.z.abs() < 0.01 && plates.plates[i].area > 1000.0)
        .collect();
    assert_eq!(walls.len(), 4, "four walls");
    // Every wall is joined to the two walls beside it (perpendicular ones).
    for &w in &walls {
        let corners = joints
            .connections
            .iter()
            .filter(|c| c.plates.contains(&(w as u32)))
            .filter(|c| {
                let o = c.plates[0] as usize + c.plates[1] as usize - w;
                walls.contains(&o)
            })
            .count();
        assert_eq!(corners, 2, "wall {w}: {:?}", joints.connections);
    }
    let bundle = state.bundle().expect("plan");
    let v = verify(&bundle.plan, state.mesh.as_deref());
    assert_eq!(v.groups, 1, "{:?}", v.problems);
    assert!(v.interference_share < 1e-3, "{}", v.interference_share);
    // No loose fragment: every part is in a joint.
    for part in &bundle.plan.parts {
        assert!(
            bundle.plan.joints.iter().any(|j| j.parts.contains(&part.id)),
            "part {} is held by no joint",
            part.id
        );
    }
}
