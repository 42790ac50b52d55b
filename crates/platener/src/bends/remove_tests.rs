//! Removing a plate already added: a net whose first-grown plate, laid flat, blocks two
//! others; every order of [`super::orders`] grows it first, removing it gives fewer parts.

use glam::{DAffine3, DVec2, DVec3};
use platener_geom::polygon::total_area;
use platener_geom::{Frame, Polygon};

use super::grow::Layout;
use crate::plan::{BendStyle, Material};
use crate::plates::{Plate, PlateKind};

const T: f64 = 3.0;

/// A 3 mm plate whose mid-plane holds `flat` (CCW, in the xy-plane) moved by `motion`.
fn plate(flat: Polygon, motion: DAffine3) -> Plate {
    Plate {
        kind: PlateKind::Inherent,
        thickness: T,
        frame: Frame {
            origin: motion.transform_point3(DVec3::new(0.0, 0.0, -T / 2.0)),
            u: motion.transform_vector3(DVec3::X),
            v: motion.transform_vector3(DVec3::Y),
            n: motion.transform_vector3(DVec3::Z),
        },
        area: flat.area(),
        polygon: flat,
        shapes: Vec::new(),
    }
}

/// The rectangle `[x0, x1] × [y0, y1]`, CCW.
fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Polygon {
    let r = |x, y| DVec2::new(x, y);
    Polygon::new(vec![r(x0, y0), r(x1, y0), r(x1, y1), r(x0, y1)])
}

/// A turn by `angle` about the line through `point` along `axis`.
fn turn(point: DVec3, axis: DVec3, angle: f64) -> DAffine3 {
    DAffine3::from_translation(point) * DAffine3::from_axis_angle(axis, angle) * DAffine3::from_translation(-point)
}

/// A 40 × 30 mm centre plate (0) with a wide flap on top (1, turned down 20°: the easiest
/// bend, the longest, and the largest plate) and a tall flap on either side (2 and 3,
/// turned up 30°). Drawn flat, the top flap reaches over both side flaps by 20 × 20 mm.
fn net() -> Vec<Plate> {
    let (x, y) = (DVec3::X, DVec3::Y);
    vec![
        plate(rect(0.0, 0.0, 40.0, 30.0), DAffine3::IDENTITY),
        plate(rect(-20.0, 30.0, 60.0, 60.0), turn(30.0 * y, x, -20f64.to_radians())),
        plate(rect(-30.0, 0.0, 0.0, 50.0), turn(DVec3::ZERO, y, 30f64.to_radians())),
        plate(rect(40.0, 0.0, 70.0, 50.0), turn(40.0 * x, y, -30f64.to_radians())),
    ]
}

#[test]
fn removing_the_plate_that_blocks_two_others_leaves_fewer_parts_than_any_order() {
    let plates = net();
    let bends = super::compute(
        &plates,
        None,
        crate::Bending::Style(BendStyle::Heat),
        Material::Acrylic,
        (1e4, 1e4),
    )
    .expect("on the grid");
    assert_eq!(bends.candidates, 3);
    // Every order alone: the top flap joins first, the side flaps stay plates (3 parts).
    let candidates = super::find::candidates(
        &plates,
        (std::f64::consts::FRAC_PI_2, std::f64::consts::FRAC_PI_2),
        None,
    );
    let zones: Vec<_> = candidates
        .iter()
        .map(|c| super::zone_of(c, &plates, BendStyle::Heat, Material::Acrylic, false))
        .collect();
    for order in super::orders(&candidates, &plates) {
        let layout = Layout::new(&plates, &candidates, &zones, (1e4, 1e4))
            .grow(&order)
            .expect("grid");
        assert_eq!(layout.quality().0, 3, "order {order:?}");
    }
    // Removing it: the centre and both side flaps are one part, the top flap a plate.
    assert_eq!(bends.parts.len(), 1, "{:#?}", bends.refused);
    let part = &bends.parts[0];
    let members: Vec<u32> = part.members.iter().map(|m| m.plate).collect();
    assert_eq!(members, [0, 2, 3]);
    assert_eq!(part.bends.len(), 2);
    // Folding back puts every corner where it was in the model.
    for m in &part.members {
        let p = &plates[m.plate as usize];
        let frame = m.flat_frame();
        for q in &p.polygon.outer {
            let model = p.frame.to_model(q.extend(T / 2.0));
            let back = frame.to_model(m.to_flat(T, model).extend(T / 2.0));
            assert!((back - model).length() < 0.01, "plate {}: {back} vs {model}", m.plate);
        }
    }
    // Laid flat the plates overlap only by the bend deduction strips along the centre's
    // 30 mm sides: the union's area is the sum of the areas less those strips.
    let developed: Vec<Polygon> = part
        .members
        .iter()
        .map(|m| m.place.apply_polygon(&m.local(&plates[m.plate as usize].polygon)))
        .collect();
    let union = platener_geom::boolean::union_all(&developed).expect("grid");
    let sum: f64 = developed.iter().map(Polygon::area).sum();
    let strips: f64 = part.bends.iter().map(|b| 30.0 * b.zone.deduction()).sum();
    assert!(strips > 0.0);
    assert!(
        (total_area(&union) - (sum - strips)).abs() < 0.05,
        "{} vs {}",
        total_area(&union),
        sum - strips
    );
}
